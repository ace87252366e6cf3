rn_add_test(kernels_conformance SOURCES unit/kernels_conformance.c
            LIBS rodnet_kernels_static LABELS unit)
