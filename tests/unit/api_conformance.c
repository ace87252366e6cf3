#include "testutil.h"
int main(void) { CHECK(0); return rn_test_finish("api_conformance (not written yet)"); }
