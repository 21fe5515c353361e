// Canonical text for exact rationals: "0", "-3", "7/16" (lowest terms, no "3/1", no "-0").
#pragma once
#include <gmpxx.h>

#include <string>

namespace vismap {

std::string canonical(const mpq_class& q);

}  // namespace vismap
