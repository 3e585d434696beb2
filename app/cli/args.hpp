// A small strict command-line parser: --flag value pairs and --switches, nothing guessed. Every error is a
// UsageError whose message names the flag; main() prints it and exits with code 2.
#pragma once

#include <array>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace impactlab::cli {

struct UsageError : std::runtime_error { using std::runtime_error::runtime_error; };

class Args {
public:
    // argv after the command name. `valued`: flags that take a value; `switches`: flags that do not;
    // `takes_files`: bare arguments are file names (fit), else a bare argument is a usage error.
    Args(const std::string& command, const std::vector<std::string>& argv, const std::set<std::string>& valued,
         const std::set<std::string>& switches = {}, bool takes_files = false);
    bool has(const std::string& flag) const;
    std::string str(const std::string& flag, const std::string& fallback) const;
    std::string required(const std::string& flag) const;
    double num(const std::string& flag, double fallback, double lo, double hi) const;
    int integer(const std::string& flag, int fallback, int lo, int hi) const;
    // "X,V": a start on the rail, x in [-0.1, 0.1] m, v in [-10, 10] m/s (as --x0, --v0).
    std::array<double, 2> pair(const std::string& flag) const;
    // "A:B" with A < B, both finite, inside [lo, hi]; `fallback` when the flag is absent.
    std::pair<double, double> range(const std::string& flag, double lo, double hi, std::pair<double, double> fallback) const;
    const std::vector<std::string>& positional() const { return positional_; }

private:
    std::string command_;
    std::map<std::string, std::string> values_;
    std::set<std::string> switches_set_;
    std::vector<std::string> positional_;
};

}  // namespace impactlab::cli
