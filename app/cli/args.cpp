#include "args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace impactlab::cli {

namespace {
// A number as strtod reads it, whole; an underflow to a subnormal or zero is that number (1e-320 is a
// number), an overflow (1e309) is not finite.
bool parse_number(const std::string& s, double& v) {
    char* end = nullptr;
    errno = 0;
    v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v)) return false;
    return !(errno == ERANGE && std::fabs(v) > 1.0);
}
// "[lo, hi]" in the shortest form (an unbounded side as -inf / inf would say nothing): "[-1, 1]", "at least 0".
std::string bounds_text(double lo, double hi) {
    std::ostringstream o;
    o.precision(6);
    if (std::isfinite(lo) && std::isfinite(hi) && std::fabs(lo) < 1e300 && std::fabs(hi) < 1e300) o << "outside [" << lo << ", " << hi << "]";
    else if (std::isfinite(lo) && std::fabs(lo) < 1e300) o << "below " << lo;
    else o << "above " << hi;
    return o.str();
}
}  // namespace

Args::Args(const std::string& command, const std::vector<std::string>& argv, const std::set<std::string>& valued,
           const std::set<std::string>& switches, bool takes_files)
    : command_(command) {
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.rfind("--", 0) != 0 || a.size() < 3) {
            if (!a.empty() && a[0] == '-' && a.size() > 1 && !std::isdigit(static_cast<unsigned char>(a[1])))
                throw UsageError(command_ + ": unknown option '" + a + "' (see: impactlab " + command_ + " --help)");
            positional_.push_back(a);
            continue;
        }
        std::string flag = a, value;
        const auto eq = a.find('=');
        bool inline_value = eq != std::string::npos;
        if (inline_value) {
            flag = a.substr(0, eq);
            value = a.substr(eq + 1);
        }
        if (switches.count(flag)) {
            if (inline_value) throw UsageError(command_ + ": option '" + flag + "' takes no value");
            switches_set_.insert(flag);
        } else if (valued.count(flag)) {
            if (!inline_value) {
                if (i + 1 >= argv.size()) throw UsageError(command_ + ": option '" + flag + "' needs a value");
                value = argv[++i];
            }
            if (values_.count(flag)) throw UsageError(command_ + ": option '" + flag + "' given twice");
            values_[flag] = value;
        } else {
            throw UsageError(command_ + ": unknown option '" + flag + "' (see: impactlab " + command_ + " --help)");
        }
    }
    if (takes_files)   // the same record twice would count as two runs of the rig
        for (std::size_t i = 0; i < positional_.size(); ++i)
            for (std::size_t j = 0; j < i; ++j) {
                std::error_code ec;
                const bool same = positional_[i] == positional_[j] ||
                                  std::filesystem::equivalent(positional_[i], positional_[j], ec);
                if (same)
                    throw UsageError(command_ + ": '" + positional_[i] + "' is given twice" +
                                     (positional_[i] == positional_[j] ? "" : " (as '" + positional_[j] + "')"));
            }
    if (!takes_files && !positional_.empty())
        throw UsageError(command_ + ": unexpected argument '" + positional_[0] + "' (options start with --; see: impactlab " +
                         command_ + " --help)");
}

bool Args::has(const std::string& flag) const { return values_.count(flag) || switches_set_.count(flag); }

std::string Args::str(const std::string& flag, const std::string& fallback) const {
    const auto it = values_.find(flag);
    return it == values_.end() ? fallback : it->second;
}

std::string Args::required(const std::string& flag) const {
    const auto it = values_.find(flag);
    if (it == values_.end()) throw UsageError(command_ + ": missing required option '" + flag + "'");
    return it->second;
}

double Args::num(const std::string& flag, double fallback, double lo, double hi) const {
    const auto it = values_.find(flag);
    if (it == values_.end()) return fallback;
    const std::string& s = it->second;
    double v = 0;
    if (!parse_number(s, v)) throw UsageError(command_ + ": option '" + flag + "': '" + s + "' is not a finite number");
    if (v < lo || v > hi) throw UsageError(command_ + ": option '" + flag + "': " + s + " is " + bounds_text(lo, hi));
    return v;
}

int Args::integer(const std::string& flag, int fallback, int lo, int hi) const {
    const auto it = values_.find(flag);
    if (it == values_.end()) return fallback;
    const std::string& s = it->second;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
        throw UsageError(command_ + ": option '" + flag + "': '" + s + "' is not an integer");
    if (v < lo || v > hi)
        throw UsageError(command_ + ": option '" + flag + "': " + s + " is outside [" + std::to_string(lo) + ", " +
                         std::to_string(hi) + "]");
    return static_cast<int>(v);
}

std::array<double, 2> Args::pair(const std::string& flag) const {
    const std::string v = str(flag, "");
    std::vector<std::string> parts;
    {
        std::stringstream ss(v);
        std::string item;
        while (std::getline(ss, item, ',')) parts.push_back(item);
    }
    if (parts.size() != 2 || parts[0].empty() || parts[1].empty())
        throw UsageError(command_ + ": option '" + flag + "': expected X,V (two numbers), got '" + v + "'");
    // A start on the rail at a speed the rig can have (as --x0 and --v0): a start beyond would only make the
    // search that begins there wander or stall.
    const double lo[2] = {-0.1, -10.0}, hi[2] = {0.1, 10.0};
    const char* what[2] = {"X", "V"};
    std::array<double, 2> y{};
    for (std::size_t i = 0; i < 2; ++i) {
        if (!parse_number(parts[i], y[i]))
            throw UsageError(command_ + ": option '" + flag + "': " + what[i] + " = '" + parts[i] + "' is not a finite number");
        if (y[i] < lo[i] || y[i] > hi[i])
            throw UsageError(command_ + ": option '" + flag + "': " + what[i] + " = " + parts[i] + " is " + bounds_text(lo[i], hi[i]) +
                             (i == 0 ? " m (the rail)" : " m/s"));
    }
    return y;
}

std::pair<double, double> Args::range(const std::string& flag, double lo, double hi, std::pair<double, double> fallback) const {
    if (!has(flag)) return fallback;
    const std::string s = str(flag, "");
    const auto colon = s.find(':');
    if (colon == std::string::npos) throw UsageError(command_ + ": option '" + flag + "': expected A:B, got '" + s + "'");
    double r[2];
    const std::string parts[2] = {s.substr(0, colon), s.substr(colon + 1)};
    for (int i = 0; i < 2; ++i) {
        if (!parse_number(parts[i], r[i]))
            throw UsageError(command_ + ": option '" + flag + "': '" + parts[i] + "' is not a finite number");
        if (r[i] < lo || r[i] > hi)
            throw UsageError(command_ + ": option '" + flag + "': " + parts[i] + " is " + bounds_text(lo, hi));
    }
    if (!(r[1] > r[0])) throw UsageError(command_ + ": option '" + flag + "': the end is not above the start");
    return {r[0], r[1]};
}

}  // namespace impactlab::cli
