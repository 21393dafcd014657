// Broken on purpose: statics does not link dynamics.
#include "engine/dynamics/world.h"
