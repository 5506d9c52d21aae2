// The failure count of a test that runs all its checks instead of stopping at the first:
// each failed check prints "FAILED: <what>" and counts, and the test exits with
// ExitStatus().

#ifndef SPTTestChecks_h
#define SPTTestChecks_h

#include <cstdlib>
#include <iostream>
#include <string>

namespace SPTTestChecks
{
class FailureCount
{
public:
  // Counts a failure, and prints what failed, unless `condition` holds. Returns `condition`.
  bool Check(bool condition, const std::string& what)
  {
    if (!condition)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++this->Count;
    }
    return condition;
  }

  int GetCount() const { return this->Count; }

  // EXIT_SUCCESS without failures; else EXIT_FAILURE, after printing how many there were.
  int ExitStatus() const
  {
    if (this->Count > 0)
    {
      std::cerr << this->Count << " check(s) failed.\n";
      return EXIT_FAILURE;
    }
    return EXIT_SUCCESS;
  }

private:
  int Count = 0;
};
}

#endif
