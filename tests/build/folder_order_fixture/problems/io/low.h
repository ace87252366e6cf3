/* fixture: an upward include (io below cli) */
#include "cli/high.h"
