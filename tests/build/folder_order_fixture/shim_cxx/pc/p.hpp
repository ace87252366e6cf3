/* fixture: downward includes */
#include "factor/f.hpp"
#include "system/s.hpp"
