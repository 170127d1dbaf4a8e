!> Program identity, written to the terminal and to every HDF5 file.
module contact2d_version
   implicit none
   private
   public :: program_name, program_version, output_format_version

   character(len=*), parameter :: program_name = 'contact2d'
   !> Semantic version of the program.
   character(len=*), parameter :: program_version = '0.1.0'
   !> Version of the HDF5 layout (SPEC section 8); bumped when a name or shape changes.
   character(len=*), parameter :: output_format_version = '1.0'
end module contact2d_version
