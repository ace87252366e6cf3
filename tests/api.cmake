# C API (c_api/): lifecycle and error paths, section constants, network-level
# conformance of energy, gradient, HVP and CSR Hessian.
rn_add_test(api_lifecycle SOURCES unit/api_lifecycle.c LIBS rodnet LABELS unit)
rn_add_test(api_sections SOURCES unit/api_sections.c LIBS rodnet LABELS unit)
rn_add_test(api_conformance SOURCES unit/api_conformance.c LIBS rodnet LABELS unit)
