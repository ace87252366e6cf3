rn_add_test(kernels_conformance SOURCES unit/kernels_conformance.c
            LIBS rodnet_kernels_static LABELS unit)
rn_add_test(kernels_joint SOURCES unit/kernels_joint.c
            LIBS rodnet_kernels_static LABELS unit)
rn_add_test(kernels_joint_net SOURCES unit/kernels_joint_net.c
            LIBS rodnet_kernels_static LABELS unit)
rn_add_test(kernels_closed_form SOURCES unit/kernels_closed_form.c
            LIBS rodnet_kernels_static LABELS unit)
rn_add_test(kernels_joint_closed SOURCES unit/kernels_joint_closed.c
            LIBS rodnet_kernels_static LABELS unit)
rn_add_test(kernels_contact SOURCES unit/kernels_contact.c
            LIBS rodnet_kernels_static LABELS unit)
