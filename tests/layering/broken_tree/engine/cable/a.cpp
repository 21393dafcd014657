// Broken on purpose: Box2D outside engine/dynamics.
#include <box2d/box2d.h>
