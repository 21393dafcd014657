// Broken on purpose: ui including the app.
#include "app/command.h"
