// The offence the check must name: a lower room including an upper one.
#include "high/high.h"
#include "low/low.h"
