!> The time step of the explicit engine, decided here and nowhere else (SPEC section 4,
!> docs/deck.md &solver): the critical step of the element bound, of mass scaling and of the
!> penalty springs; dt from solver:dt or solver:dt_factor, checked against solver:allow_unstable;
!> the power-iteration estimate of the true limit and solver:dt_limit = 'power'; the fallback
!> step after a growing mode. model_build and the explicit run call it.
module contact2d_timestep
   use contact2d_kinds, only: wp
   use contact2d_strings, only: str
   use contact2d_messages, only: messages_t
   use contact2d_deck, only: deck_t
   use contact2d_stiffness, only: stiffness_t
   use contact2d_contact, only: contact_t
   implicit none
   private
   public :: timestep_critical, timestep_choose, timestep_power, timestep_guarded, timestep_fallback

contains

   !> The critical step [s]: the element bound 2/omega_max, or with mass scaling the bound of the
   !> scaled system dt_scaled where it is the larger (both hold: added mass only lowers
   !> omega_max); with penalty springs k_p w_i at the contact nodes the nodal bound
   !> dt <= 2 / sqrt(omega_max^2 + k_p w_i / m_i), with omega_max^2 of the scaled system when mass
   !> scaling gives the larger step.
   real(wp) function timestep_critical(stiff, contact, dt_scaled) result(dt_critical)
      type(stiffness_t), intent(in) :: stiff
      type(contact_t), intent(in) :: contact
      real(wp), intent(in) :: dt_scaled   !< stable step of mass scaling [s] (0: none)
      real(wp) :: omega2
      dt_critical = stiff%dt_critical()
      dt_critical = max(dt_critical, dt_scaled)
      if (contact%penalty) then
         omega2 = stiff%omega2_element
         if (dt_scaled > stiff%dt_critical()) omega2 = (2/dt_scaled)**2
         dt_critical = 2/sqrt(omega2 + maxval(contact%penalty_stiffness*contact%weight/contact%mass))
      end if
   end function timestep_critical

   !> dt = solver:dt, or solver:dt_factor dt_critical when it is 0; a dt above dt_critical is
   !> refused (stat = 1, one line naming both) unless solver:allow_unstable, then warned about.
   subroutine timestep_choose(deck, dt_critical, penalty, dt, warnings, stat, errmsg)
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: dt_critical   !< [s]
      logical, intent(in) :: penalty        !< dt_critical includes penalty springs (named so)
      real(wp), intent(out) :: dt           !< [s]
      type(messages_t), intent(inout) :: warnings
      integer, intent(out) :: stat
      character(len=:), allocatable, intent(out) :: errmsg
      stat = 0
      errmsg = ''
      if (deck%solver%dt > 0) then
         dt = deck%solver%dt
      else
         dt = deck%solver%dt_factor*dt_critical
      end if
      if (dt > dt_critical .and. .not. deck%solver%allow_unstable) then
         stat = 1
         errmsg = deck%path//': solver: dt = '//str(dt)//' s exceeds '// &
                  trim(merge('the penalty-adjusted dt_critical', 'dt_critical                     ', penalty))// &
                  ' = '//str(dt_critical)//' s (ratio '//str(anint(1000*(dt/dt_critical))/1000)// &
                  '); set solver:allow_unstable = .true. to run anyway'
         return
      end if
      if (dt > dt_critical) then
         call warnings%add('dt = '//str(dt/dt_critical)//' dt_critical: '// &
                           'allowed by solver:allow_unstable, the run may blow up')
      end if
   end subroutine timestep_choose

   !> solver:power_iterations > 0: omega2_power, the power-iteration estimate of omega_max^2 of
   !> M^-1 K on the free dofs (with the penalty springs k_p w_i n_i^2 on the contact nodes' dofs,
   !> all closed), else 0. solver:dt_limit = 'power' with solver:dt = 0: dt from that estimate,
   !> dt_factor 2/omega_max, never below the step given (the element-bound step).
   subroutine timestep_power(deck, stiff, free, contacts, dt, omega2_power)
      type(deck_t), intent(in) :: deck
      type(stiffness_t), intent(in) :: stiff
      real(wp), intent(in), contiguous :: free(:, :)   !< (2, nnode): 1 on free dofs
      type(contact_t), intent(in) :: contacts(:)        !< the contact pairs' operators
      real(wp), intent(inout) :: dt                     !< [s]
      real(wp), intent(out) :: omega2_power             !< [1/s^2]
      real(wp), allocatable :: extra(:, :)
      integer :: i, k
      omega2_power = 0
      if (deck%solver%power_iterations > 0) then
         if (any(contacts%penalty)) then
            allocate (extra(2, size(free, 2)))
            extra = 0
            ! each pair's springs on its own nodes (the slave sets are disjoint)
            do k = 1, size(contacts)
               if (.not. contacts(k)%penalty) cycle
               associate (contact => contacts(k))
                  do i = 1, contact%nc
                     extra(:, contact%node(i)) = contact%penalty_stiffness*contact%weight(i)*contact%normal(:, i)**2
                  end do
               end associate
            end do
            omega2_power = stiff%power_omega2(free, deck%solver%power_iterations, extra)
         else
            omega2_power = stiff%power_omega2(free, deck%solver%power_iterations)
         end if
      end if
      if (deck%solver%dt_limit == 'power' .and. deck%solver%dt == 0 .and. omega2_power > 0) then
         dt = max(dt, deck%solver%dt_factor*2/sqrt(omega2_power))
      end if
   end subroutine timestep_power

   !> The growing-mode guard watches only a step taken from the power estimate above the
   !> element-bound step (never a dt the user gave).
   logical function timestep_guarded(deck, dt, dt_critical) result(guard)
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: dt, dt_critical   !< [s]
      guard = deck%solver%dt_limit == 'power' .and. deck%solver%dt == 0 .and. &
              dt > deck%solver%dt_factor*dt_critical*(1 + 1.0e-12_wp)
   end function timestep_guarded

   !> The step after a growing mode: back to the element bound, dt_factor dt_critical [s].
   real(wp) function timestep_fallback(deck, dt_critical) result(dt)
      type(deck_t), intent(in) :: deck
      real(wp), intent(in) :: dt_critical   !< [s]
      dt = deck%solver%dt_factor*dt_critical
   end function timestep_fallback
end module contact2d_timestep
