#include "beginner_tutorials/checked_int.h"

#include <cerrno>
#include <cstdlib>
#include <limits>

namespace beginner_tutorials
{
bool parseInt64(const std::string& text, int64_t* value)
{
  const size_t digits_start = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
  if (text.size() == digits_start)
    return false;
  for (size_t i = digits_start; i < text.size(); ++i)
  {
    if (text[i] < '0' || text[i] > '9')
      return false;
  }
  errno = 0;
  const long long parsed = std::strtoll(text.c_str(), nullptr, 10);
  if (errno == ERANGE)
    return false;
  *value = static_cast<int64_t>(parsed);
  return true;
}

bool checkedAdd(int64_t a, int64_t b, int64_t* sum)
{
  if ((b > 0 && a > std::numeric_limits<int64_t>::max() - b) || (b < 0 && a < std::numeric_limits<int64_t>::min() - b))
    return false;
  *sum = a + b;
  return true;
}

}  // namespace beginner_tutorials
