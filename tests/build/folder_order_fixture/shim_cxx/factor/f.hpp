/* fixture: an include at the same level (factor, krylov independent) */
#include "krylov/k.hpp"
