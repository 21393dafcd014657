// Broken on purpose: the engine including the UI.
#include "ui/renderer.h"
