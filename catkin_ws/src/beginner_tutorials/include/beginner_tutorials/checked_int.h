#ifndef BEGINNER_TUTORIALS_CHECKED_INT_H
#define BEGINNER_TUTORIALS_CHECKED_INT_H

#include <cstdint>
#include <string>

namespace beginner_tutorials
{
/// The longest wait for a service that the clients accept, in seconds (one day).
constexpr double kMaxTimeout = 86400.0;

/// Parses a whole decimal integer ("42", "-7", "+3"). False for anything else: empty text, spaces,
/// other characters, or a value outside int64.
bool parseInt64(const std::string& text, int64_t* value);

/// Sets *sum = a + b and returns true, or returns false when the sum does not fit in int64.
bool checkedAdd(int64_t a, int64_t b, int64_t* sum);

}  // namespace beginner_tutorials

#endif  // BEGINNER_TUTORIALS_CHECKED_INT_H
