# C API (c_api/): lifecycle and error paths, section constants, network-level
# conformance of energy, gradient, HVP and CSR Hessian, per-stencil result fields,
# joints (both models: FD table, reference update, BCs, loads, error paths),
# component pins.
rn_add_test(api_lifecycle SOURCES unit/api_lifecycle.c LIBS rodnet LABELS unit)
rn_add_test(api_sections SOURCES unit/api_sections.c LIBS rodnet LABELS unit)
# The planar model (rodnet_model.h): requests, free DOFs, qualification report.
rn_add_test(api_planar SOURCES unit/api_planar.c LIBS rodnet m LABELS unit)
rn_add_test(api_conformance SOURCES unit/api_conformance.c LIBS rodnet LABELS unit)
rn_add_test(api_fields SOURCES unit/api_fields.c LIBS rodnet LABELS unit)
rn_add_test(api_joints SOURCES unit/api_joints.c LIBS rodnet LABELS unit)
rn_add_test(api_overflow SOURCES unit/api_overflow.c LIBS rodnet LABELS unit)
rn_add_test(api_components SOURCES unit/api_components.c LIBS rodnet m LABELS unit)
rn_add_test(api_load_increment SOURCES unit/api_load_increment.c LIBS rodnet m LABELS unit)
# rn_network_dofs_load_factor (rodnet_ramp.h): finalize, set_dofs, update_reference,
# state restore; unchanged by load factor changes and failed updates.
rn_add_test(api_dofs_load_factor SOURCES unit/api_dofs_load_factor.c LIBS rodnet m
            LABELS unit)
# Parts of a network (distributed solves) built in one process: sums of the
# parts' energies, gradients, HVPs and Hessians by global DOF against the whole
# network, before and after reference updates; ownership counts.
rn_add_test(api_part SOURCES unit/api_part.c LIBS rodnet m LABELS unit)
# Rod / interface classification of the reduced DOFs (domain decomposition).
rn_add_test(api_dof_blocks SOURCES unit/api_dof_blocks.c LIBS rodnet m LABELS unit)
# Equilibrium checks: DOF kinds, the full-layout gradient, support reactions
# (FD h-sweep in the load factor of prescribed motions, balance at equilibrium).
if(RN_WITH_TRILINOS) # it solves (rn_solve) to check the balance at equilibrium
  rn_add_test(api_reactions SOURCES unit/api_reactions.c LIBS rodnet m LABELS unit)
endif()
# rn_network_stretch_correction against the stretching energy (h-sweep, order 2)
# on a rod and on networks with both joint models; its closed-form limit.
rn_add_test(api_stretch_correction SOURCES unit/api_stretch_correction.c LIBS rodnet m
            LABELS unit)
# Periodic cells: rod ends at periodic images, macroscopic strain DOFs (FD
# h-sweeps over fluctuation and strain DOFs, images, uniform strain, errors).
rn_add_test(api_periodic SOURCES unit/api_periodic.c LIBS rodnet m LABELS unit)
# Contact (rodnet_contact.h): FD h-sweeps of the network with contact pairs
# (crossing rods, a hairpin in self contact), CSR Hessian = HVP, the closed-form
# gap, the continuous check against tunnelling, errors.
rn_add_test(api_contact SOURCES unit/api_contact.c LIBS rodnet m LABELS unit)
# Closed rods and smooth joints (issue 10 section 4): derivatives (h-sweep), a
# free ring at its rest polygon, two rods closed by smooth joints against the
# closed rod, link conservation over large rotations, Michell's twisted ring.
rn_add_test(api_rings SOURCES unit/api_rings.c LIBS rodnet ${LAPACK_LIBRARIES} m
            LABELS unit validation)
rn_add_test(api_couple_fixed SOURCES unit/api_couple_fixed.c LIBS rodnet LABELS unit)
if(RN_WITH_TRILINOS) # the refusals of the solver's entry points (rn_homogenize, ...)
  target_compile_definitions(api_couple_fixed PRIVATE RN_TEST_SOLVER=1)
endif()
# The Hessian pattern of a periodic supercell: work linear in its size, counted
# (docs/homogenization.md, "Reading large supercells").
rn_add_test(api_pattern_linear SOURCES unit/api_pattern_linear.c
            LIBS rodnet_internal m LABELS unit)
target_include_directories(api_pattern_linear PRIVATE
                           ${CMAKE_CURRENT_SOURCE_DIR}/../kernels
                           ${CMAKE_CURRENT_SOURCE_DIR}/../c_api)
