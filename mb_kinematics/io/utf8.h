// Where the UTF-8 checks were before the core's messages needed them (core/printable.h).
#pragma once

#include "mb_kinematics/core/utf8.h"
