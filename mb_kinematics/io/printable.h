// Where printable() was before the core's own messages needed it (they hold model names).
#pragma once

#include "mb_kinematics/core/printable.h"
