// The measured-data loader: MODEL.md's CSV conventions, explicit column mapping, strict checks.
#include <algorithm>
#include <charconv>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "impactlab/identify_data.hpp"
#include "impactlab/input_file.hpp"

namespace impactlab::identify {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
    return s;
}

std::string_view unquote(std::string_view s) {
    s = trim(s);
    if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = trim(s.substr(1, s.size() - 2));
    return s;
}

void split(std::string_view line, std::vector<std::string_view>& fields) {
    fields.clear();
    std::size_t start = 0;
    for (;;) {
        const std::size_t comma = line.find(',', start);
        if (comma == std::string_view::npos) {
            fields.push_back(line.substr(start));
            return;
        }
        fields.push_back(line.substr(start, comma - start));
        start = comma + 1;
    }
}

[[noreturn]] void fail(const std::string& source, long line, const std::string& what) {
    throw DataError(source + (line > 0 ? ": line " + std::to_string(line) : std::string()) + ": " + what);
}

bool all_digits(const std::string& s) {
    return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// A number taken whole, as std::from_chars reads it. Emscripten's libc++ has no floating-point from_chars
// (the browser page reads records too): there strtod on a terminated copy, refusing what from_chars would
// (leading space, hexadecimal), with an overflow or underflow out of range as from_chars reports it.
std::from_chars_result read_double(const char* first, const char* last, double& v) {
#ifdef __EMSCRIPTEN__
    const std::string text(first, last);
    if (text.empty() || std::isspace(static_cast<unsigned char>(text[0])) || text.find_first_of("xX") != std::string::npos)
        return {first, std::errc::invalid_argument};
    char* end = nullptr;
    errno = 0;
    const double r = std::strtod(text.c_str(), &end);
    if (end == text.c_str()) return {first, std::errc::invalid_argument};
    if (errno == ERANGE) return {first + (end - text.c_str()), std::errc::result_out_of_range};
    v = r;
    return {first + (end - text.c_str()), std::errc()};
#else
    return std::from_chars(first, last, v);
#endif
}

std::string show(std::string_view s) {
    std::string out(s.substr(0, 40));
    if (s.size() > 40) out += "...";
    return "'" + out + "'";
}

}  // namespace

void parse_row_range(const std::string& spec, long& begin, long& end) {
    const auto colon = spec.find(':');
    if (colon == std::string::npos) throw DataError("row range '" + spec + "': expected A:B (0-based, B excluded)");
    auto num = [&](const std::string& s, long fallback) {
        if (s.empty()) return fallback;
        long v = 0;
        const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
        if (r.ec != std::errc() || r.ptr != s.data() + s.size() || v < 0)
            throw DataError("row range '" + spec + "': '" + s + "' is not a row number >= 0");
        return v;
    };
    begin = num(spec.substr(0, colon), 0);
    end = num(spec.substr(colon + 1), -1);
    if (end >= 0 && end <= begin) throw DataError("row range '" + spec + "': empty (B must exceed A)");
}

std::string read_data_file(const std::string& path) {
    std::string bytes;
    try {
        bytes = read_input_file(path, kMaxInputBytes);
    } catch (const InputFileError& e) {
        throw DataError(e.what());
    }
    return is_gzip(bytes) ? gunzip(bytes, path, kMaxInputBytes) : bytes;
}

MeasuredData load_measured(const std::string& path, const LoadOptions& options) {
    return parse_measured(read_data_file(path), path, options);
}

namespace {

// The signals a record's columns map to, in the order their checks name them.
enum Sig { T, X, PHI, U, OMEGA, V, NSIG };
constexpr const char* kSigName[NSIG] = {"t", "x", "phi", "u", "omega", "v"};

// A record's table as read: the header, the column of each signal (-1: none), each signal's values and the
// file line of each data row.
struct Table {
    std::string src;
    std::vector<std::string> header;
    long header_line = 0;
    std::size_t ncols = 0;
    int col[NSIG] = {-1, -1, -1, -1, -1, -1};
    std::vector<double> rows[NSIG];
    std::vector<long> lines;
    bool free_run = false;   // no forcing column: u = 0 throughout
};

// The header's names checked, and each signal mapped to its column (by name, by the mapping given, or by
// number), with every conflict named.
void map_columns(Table& tb, const LoadOptions& opt) {
    const std::string& src = tb.src;
    const std::vector<std::string>& header = tb.header;
    const long header_line = tb.header_line;
    int* col = tb.col;
    const std::string* mapped[NSIG] = {&opt.columns.t, &opt.columns.x, &opt.columns.phi,
                                       &opt.columns.u, &opt.columns.omega, &opt.columns.v};
    // Empty names are allowed only at the end (a trailing comma on every line).
    std::size_t named = header.size();
    while (named > 0 && header[named - 1].empty()) --named;
    std::unordered_map<std::string_view, std::size_t> seen;   // linear in the columns (100k of them)
    for (std::size_t k = 0; k < named; ++k) {
        if (header[k].empty()) fail(src, header_line, "column " + std::to_string(k + 1) + " of the header has no name");
        if (!seen.emplace(header[k], k).second)
            fail(src, header_line, "column name '" + header[k] + "' appears twice (columns " +
                                       std::to_string(seen[header[k]] + 1) + " and " + std::to_string(k + 1) + ")");
    }
    auto list = [&] {
        std::string s;
        for (std::size_t k = 0; k < named; ++k) s += (k ? ", " : "") + header[k];
        return s;
    };
    for (int s = 0; s < NSIG; ++s) {
        const std::string& m = *mapped[s];
        if (m.empty()) {
            for (std::size_t k = 0; k < named; ++k)
                if (header[k] == kSigName[s]) col[s] = static_cast<int>(k);
            continue;
        }
        if (all_digits(m)) {
            const long k = m.size() > 9 ? 0 : std::stol(m);   // longer: beyond any header (and stol's range)
            if (k < 1 || static_cast<std::size_t>(k) > named)
                fail(src, header_line, std::string("the mapping of '") + kSigName[s] + "' to column " + m +
                                           " names no column (the header has " + std::to_string(named) +
                                           " columns: " + list() + ")");
            col[s] = static_cast<int>(k - 1);
        } else {
            const std::string want(unquote(m));
            for (std::size_t k = 0; k < named; ++k)
                if (header[k] == want) col[s] = static_cast<int>(k);
            if (col[s] < 0)
                fail(src, header_line, std::string("the mapping of '") + kSigName[s] + "' to column '" + m +
                                           "' names no column (the header has: " + list() + ")");
        }
    }
    for (int s = 0; s < NSIG; ++s)
        for (int r = 0; r < s; ++r)
            if (col[s] >= 0 && col[s] == col[r])
                fail(src, header_line, std::string("'") + kSigName[r] + "' and '" + kSigName[s] +
                                           "' are mapped to the same column");
    if (col[X] < 0) fail(src, header_line, "no position column 'x' (the header has: " + list() + "; map one with --x-col)");
    if (col[T] < 0 && !(opt.rate > 0))
        fail(src, header_line, "no time column 't' and no sample rate (give --rate HZ or map --t-col)");
    if (col[T] >= 0 && opt.rate > 0)
        fail(src, header_line, "both a time column and a sample rate are given; use one");
    if (col[PHI] >= 0 && col[U] >= 0) {
        if (!opt.columns.phi.empty() && opt.columns.u.empty()) col[U] = -1;
        else if (!opt.columns.u.empty() && opt.columns.phi.empty()) col[PHI] = -1;
        else fail(src, header_line, "both a 'phi' and a 'u' column: say which is the forcing (--phi-col or --u-col)");
    }
    if (opt.free_run && (col[PHI] >= 0 || col[U] >= 0))
        fail(src, header_line,
             std::string("a free run was declared (--free), but column '") +
                 header[static_cast<std::size_t>(col[PHI] >= 0 ? col[PHI] : col[U])] + "' is its forcing");
    if (col[PHI] < 0 && col[U] < 0) {
        // Only motion in the record (no column left unread): nothing forced it, a free decay. A column left
        // unread may be the forcing under another name, so there the user says which.
        bool motion_only = true;
        for (std::size_t k = 0; k < named; ++k)
            if (std::find(col, col + NSIG, static_cast<int>(k)) == col + NSIG) motion_only = false;
        if (!opt.free_run && !motion_only)
            fail(src, header_line,
                 "no forcing column: need the unbalance angle 'phi' or a measured input 'u' (the header has: " + list() +
                     "; map one with --phi-col or --u-col, or declare a free run with --free)");
        tb.free_run = true;
    }
    tb.ncols = header.size();
}

// One data row's fields: each mapped signal's value, a finite number.
void read_row(Table& tb, const std::vector<std::string_view>& fields, long lineno) {
    const std::string& src = tb.src;
    if (fields.size() != tb.ncols)
        fail(src, lineno, std::to_string(fields.size()) + " fields, but the header (line " + std::to_string(tb.header_line) +
                              ") has " + std::to_string(tb.ncols));
    for (int s = 0; s < NSIG; ++s) {
        if (tb.col[s] < 0) continue;
        std::string_view f = unquote(fields[static_cast<std::size_t>(tb.col[s])]);
        const std::string name = "column '" + tb.header[static_cast<std::size_t>(tb.col[s])] + "' (" + kSigName[s] + ")";
        if (f.empty()) fail(src, lineno, name + " is empty");
        if (f.front() == '+') f.remove_prefix(1);
        double v = 0;
        const auto r = read_double(f.data(), f.data() + f.size(), v);
        if (r.ec == std::errc::result_out_of_range) fail(src, lineno, name + ": " + show(f) + " is out of range");
        if (r.ec != std::errc() || r.ptr != f.data() + f.size()) fail(src, lineno, name + ": " + show(f) + " is not a number");
        if (!std::isfinite(v)) fail(src, lineno, name + ": " + show(f) + " is not a finite number");
        tb.rows[s].push_back(v);
    }
    tb.lines.push_back(lineno);
}

// The text's lines: comments' "key: value" pairs into d.meta, the header, then the data rows.
void read_lines(std::string_view text, Table& tb, MeasuredData& d, const LoadOptions& opt) {
    std::vector<std::string_view> fields;
    long lineno = 0;
    std::size_t pos = 0;
    // Lines end in LF, CRLF or (old Mac files) a lone CR.
    const char eol_char = text.find('\n') == std::string_view::npos && text.find('\r') != std::string_view::npos ? '\r' : '\n';
    while (pos < text.size()) {
        std::size_t eol = text.find(eol_char, pos);
        if (eol == std::string_view::npos) eol = text.size();
        std::string_view line = text.substr(pos, eol - pos);
        pos = eol + 1;
        ++lineno;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::string_view tl = trim(line);
        if (tl.empty()) continue;
        if (tl.front() == '#') {
            const std::string_view body = trim(tl.substr(1));
            const auto colon = body.find(':');
            if (colon != std::string_view::npos && colon > 0) {
                const std::string key(trim(body.substr(0, colon)));
                if (key.find(' ') == std::string::npos) d.meta[key] = std::string(trim(body.substr(colon + 1)));
            }
            continue;
        }
        split(line, fields);
        if (tb.header.empty()) {
            tb.header_line = lineno;
            for (auto f : fields) tb.header.emplace_back(unquote(f));
            map_columns(tb, opt);
            continue;
        }
        read_row(tb, fields, lineno);
    }
}

// Whole-file checks, before any row selection: time increases, phi is the unwrapped angle.
void check_whole_file(const Table& tb, const LoadOptions& opt) {
    const std::size_t n = tb.lines.size();
    const auto& rows = tb.rows;
    const auto& lines = tb.lines;
    if (tb.col[T] >= 0) {
        for (std::size_t i = 1; i < n; ++i)
            if (!(rows[T][i] > rows[T][i - 1])) {
                std::ostringstream msg;
                msg << std::setprecision(10) << "time does not increase: t = " << rows[T][i] << " after t = " << rows[T][i - 1]
                    << " (line " << lines[i - 1] << ")";
                fail(tb.src, lines[i], msg.str());
            }
    }
    if (tb.col[PHI] >= 0) {
        for (std::size_t i = 1; i < n; ++i) {
            const double jump = (rows[PHI][i] - rows[PHI][i - 1]) * opt.phi_scale;
            if (std::abs(jump) > 3.141592653589793) {
                std::ostringstream msg;
                msg << std::setprecision(6) << "phi jumps by " << jump
                    << " rad from the previous sample: phi must be the unwrapped, continuous angle";
                fail(tb.src, lines[i], msg.str());
            }
        }
    }
}

// Signal s over rows [b, e), scaled: every value representable, within what any sensor reads, and none a
// million times the record's spread from its median (a corrupt sample).
void take(const Table& tb, int s, double scale, std::size_t b, std::size_t e, std::vector<double>& out) {
    const std::string& src = tb.src;
    const auto& rows = tb.rows;
    const auto& lines = tb.lines;
    if (tb.col[s] < 0) return;
    const std::string& name = tb.header[static_cast<std::size_t>(tb.col[s])];
    out.assign(rows[s].begin() + static_cast<long>(b), rows[s].begin() + static_cast<long>(e));
    if (scale != 1.0)
        for (std::size_t i = 0; i < out.size(); ++i) {
            out[i] *= scale;
            if (!std::isfinite(out[i]) || (out[i] == 0.0) != (rows[s][b + i] == 0.0)) {
                std::ostringstream msg;
                msg << "column '" << name << "' (" << kSigName[s] << "): "
                    << rows[s][b + i] << " times the scale " << scale << " is not a representable number";
                fail(src, lines[b + i], msg.str());
            }
        }
    // No sensor in any unit reads beyond 1e15; a value a million times beyond the record's own spread is a
    // corrupt sample, not a measurement. Both would overflow the fit's sums of squares.
    if (s == X || s == U || s == V)
        for (std::size_t i = 0; i < out.size(); ++i)
            if (!(std::abs(out[i]) <= 1e15)) {
                std::ostringstream msg;
                msg << "column '" << name << "' (" << kSigName[s] << "): " << out[i]
                    << " lies beyond 1e15: not a measurement in any unit";
                fail(src, lines[b + i], msg.str());
            }
    if (s != T && out.size() >= 8) {
        std::vector<double> sorted(out);
        std::sort(sorted.begin(), sorted.end());
        const double med = sorted[sorted.size() / 2];
        const double q_lo = sorted[sorted.size() / 100], q_hi = sorted[sorted.size() - 1 - sorted.size() / 100];
        const double spread = std::max(q_hi - q_lo, 1e-300 + 1e-12 * std::abs(med));
        for (std::size_t i = 0; i < out.size(); ++i)
            if (std::abs(out[i] - med) > 1e6 * spread) {
                std::ostringstream msg;
                msg << "column '" << name << "' (" << kSigName[s] << "): " << out[i]
                    << " lies " << std::abs(out[i] - med) / spread << " times the record's spread (" << spread
                    << ") from its median: a corrupt sample; remove the row or select rows with --rows";
                fail(src, lines[b + i], msg.str());
            }
    }
}

// Time in seconds: a record within a few decades, samples at least a nanosecond apart (a unit slip makes
// the sample count of the span overflow every array sized from it).
void check_time_unit(const Table& tb, const MeasuredData& d, std::size_t b) {
    for (std::size_t i = 0; i < d.t.size(); ++i) {
        const bool too_far = !(std::abs(d.t[i]) <= 1e9);
        const bool too_close = i > 0 && !(d.t[i] - d.t[i - 1] >= 1e-9);
        if (too_far || too_close) {
            std::ostringstream msg;
            msg << std::setprecision(10) << "time t = " << d.t[i] << " s"
                << (too_far ? " lies beyond 1e9 s (30 years) of the record's zero"
                            : " is within 1 ns of the previous sample")
                << ": time must be in seconds (--t-scale, or --rate for a file without time)";
            fail(tb.src, tb.col[T] >= 0 ? tb.lines[b + i] : 0, msg.str());
        }
    }
}

}  // namespace

MeasuredData parse_measured(std::string_view text, const std::string& src, const LoadOptions& opt) {
    MeasuredData d;
    d.source = src;
    if (text.size() >= 3 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);   // UTF-8 BOM
    if (text.find('\0') != std::string_view::npos) fail(src, 0, "not a text file (it contains NUL bytes)");
    Table tb;
    tb.src = src;
    read_lines(text, tb, d, opt);
    if (tb.header.empty()) fail(src, 0, "no header row (the file is empty or holds only comments)");
    const std::size_t n = tb.lines.size();
    if (n == 0) fail(src, 0, "no data rows after the header (line " + std::to_string(tb.header_line) + ")");
    check_whole_file(tb, opt);

    const std::size_t b = static_cast<std::size_t>(std::max(0L, opt.row_begin));
    const std::size_t e = opt.row_end < 0 ? n : static_cast<std::size_t>(opt.row_end);
    if (b >= n || e > n)
        fail(src, 0, "rows " + std::to_string(opt.row_begin) + ":" + (opt.row_end < 0 ? "" : std::to_string(opt.row_end)) +
                         " lie outside the file's " + std::to_string(n) + " data rows");
    if (e - b < opt.min_samples)
        fail(src, 0, "only " + std::to_string(e - b) + " samples; at least " + std::to_string(opt.min_samples) + " are needed");

    if (tb.col[T] >= 0) {
        take(tb, T, opt.t_scale, b, e, d.t);
    } else {
        d.t.resize(e - b);
        for (std::size_t i = b; i < e; ++i) d.t[i - b] = static_cast<double>(i) / opt.rate;
    }
    take(tb, X, opt.x_scale, b, e, d.x);
    take(tb, PHI, opt.phi_scale, b, e, d.phi);
    take(tb, U, opt.u_scale, b, e, d.u);
    if (tb.free_run) {
        d.u.assign(d.t.size(), 0.0);
        d.free_run = true;
        d.meta["forcing"] = "none: a free run (no forcing column), input u = 0";
    }
    take(tb, OMEGA, 1.0, b, e, d.omega);
    take(tb, V, opt.x_scale, b, e, d.v);
    check_time_unit(tb, d, b);
    d.line.assign(tb.lines.begin() + static_cast<long>(b), tb.lines.begin() + static_cast<long>(e));
    return d;
}

MeasuredData join_records(const std::vector<MeasuredData>& runs) {
    if (runs.empty()) throw DataError("no data: give at least one record");
    if (runs.size() == 1) return runs.front();
    MeasuredData all;
    all.run_starts.clear();
    const bool phi = runs.front().has_phi();
    double dt0 = 0;
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const MeasuredData& r = runs[k];
        if (r.size() < 2) throw DataError(r.source + ": a run needs at least two samples");
        if (r.has_phi() != phi)
            throw DataError(r.source + ": forced through " + (r.has_phi() ? "phi" : "u") + ", but " + runs.front().source +
                            " through " + (phi ? "phi" : "u") + ": runs fitted together need the same forcing");
        const double dt = (r.t.back() - r.t.front()) / static_cast<double>(r.size() - 1);
        if (k == 0) dt0 = dt;
        if (std::abs(dt - dt0) > 0.01 * dt0)
            throw DataError(r.source + ": sample step " + std::to_string(dt) + " s, but " + runs.front().source + " has " +
                            std::to_string(dt0) + " s: runs fitted together need the same rate");
        const double shift = k == 0 ? 0.0 : all.t.back() + dt0 - r.t.front();
        all.run_starts.push_back(all.t.size());
        all.run_sources.push_back(r.source);
        for (std::size_t i = 0; i < r.size(); ++i) all.t.push_back(r.t[i] + shift);
        all.x.insert(all.x.end(), r.x.begin(), r.x.end());
        all.phi.insert(all.phi.end(), r.phi.begin(), r.phi.end());
        all.u.insert(all.u.end(), r.u.begin(), r.u.end());
        all.omega.insert(all.omega.end(), r.omega.begin(), r.omega.end());
        all.v.insert(all.v.end(), r.v.begin(), r.v.end());
        all.line.insert(all.line.end(), r.line.begin(), r.line.end());
        all.source += (k ? " + " : "") + r.source;
        for (const auto& [key, value] : r.meta) all.meta[r.source + ": " + key] = value;
    }
    all.free_run = std::all_of(runs.begin(), runs.end(), [](const MeasuredData& r) { return r.free_run; });
    // An optional column only some runs have is dropped (its samples would not line up).
    if (all.omega.size() != all.t.size()) all.omega.clear();
    if (all.v.size() != all.t.size()) all.v.clear();
    return all;
}

void write_measured_csv(std::ostream& out, const MeasuredData& d) {
    for (const auto& [k, v] : d.meta) out << "# " << k << ": " << v << '\n';
    out << "t,x," << (d.has_phi() ? "phi" : "u") << '\n';
    const auto& f = d.has_phi() ? d.phi : d.u;
    char buf[96];
    for (std::size_t i = 0; i < d.size(); ++i) {
        const int len = std::snprintf(buf, sizeof buf, "%.6f,%.7f,%.6f\n", d.t[i], d.x[i], f[i]);
        out.write(buf, len);
    }
}

}  // namespace impactlab::identify
