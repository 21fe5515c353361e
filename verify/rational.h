// The spec's canonical rational strings: "0", "-3", "7/16".
#pragma once
#include <gmpxx.h>

#include <string>
#include <string_view>

namespace vismap_check {

// True and sets `out` iff `s` is canonical: optional '-', no leading zeros, a
// denominator > 1 only when needed, lowest terms, never "-0". Otherwise sets `why`.
bool parse_canonical(std::string_view s, mpq_class& out, std::string& why);

// Canonical form of a canonicalized mpq (what messages print).
std::string str(const mpq_class& q);

}  // namespace vismap_check
