// The checker moved to verify/ (library vismap_verify, `vismap verify`).
// Kept so that tests written against the old path still build.
#pragma once
#include "verify/checker.h"
