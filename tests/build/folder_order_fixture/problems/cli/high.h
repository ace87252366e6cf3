/* fixture: the higher folder */
#include "io/low.h"
