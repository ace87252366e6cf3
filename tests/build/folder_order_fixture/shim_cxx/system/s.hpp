/* fixture: an upward include listed as an exception */
#include "pc/p.hpp"
