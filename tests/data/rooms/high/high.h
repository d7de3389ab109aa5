// A header of the upper room: it may include the lower one.
#pragma once
#include "low/low.h"
