!> contact2d: explicit dynamics of a Q1 plane-strain body against a rigid obstacle.
program contact2d_main
   use contact2d_driver, only: driver_main
   implicit none
   call driver_main()
end program contact2d_main
