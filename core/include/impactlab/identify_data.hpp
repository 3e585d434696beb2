// Measured data for impactlab fit: the CSV conventions of MODEL.md, column mapping for other layouts,
// gzip read directly. A file that breaks the rules is refused with its line number and the problem
// (DataError); nothing is guessed.
#pragma once

#include <cstddef>
#include <map>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace impactlab::identify {

struct DataError : std::runtime_error { using std::runtime_error::runtime_error; };

// Which file column holds which signal. Empty: the conventional name (t, x, phi, u, omega, v). Otherwise a
// header name (quotes and surrounding spaces ignored) or a 1-based column number ("2").
struct ColumnMap {
    std::string t, x, phi, u, omega, v;
};

struct LoadOptions {
    ColumnMap columns;
    double rate = 0.0;          // [Hz] sample rate for a file without a time column (then required)
    double t_scale = 1.0;       // multiplies the time column (e.g. 1e-3 for ms)
    double x_scale = 1.0;       // multiplies x (and v) (e.g. 1e-3 for mm)
    double phi_scale = 1.0;     // multiplies phi (e.g. pi/180 for degrees)
    double u_scale = 1.0;       // multiplies u
    long row_begin = 0;         // data rows [row_begin, row_end), 0-based like a Python slice; the whole
    long row_end = -1;          // file is still checked; -1: to the end
    std::size_t min_samples = 32;
    // A free run (a decay from an initial displacement): no forcing was applied, u = 0 throughout. A record
    // whose columns are all motion (t, x, v, omega) is read so without it; this says so where others are present.
    bool free_run = false;
};

struct MeasuredData {
    std::string source;                         // file name (for messages)
    std::vector<double> t, x;                   // [s], [m]
    std::vector<double> phi;                    // [rad], unwrapped; empty if the forcing is u
    std::vector<double> u;                      // measured input; empty if the forcing is phi
    std::vector<double> omega, v;               // optional columns; empty if absent
    std::vector<long> line;                     // the file line of each sample (1-based)
    std::map<std::string, std::string> meta;    // "# key: value" comment lines
    // Several runs of one rig fitted together (join_records): the first sample of each run. Each run keeps
    // its own forcing and initial state; nothing (smoothing, windows, impacts) reaches across a start.
    std::vector<std::size_t> run_starts{0};
    std::vector<std::string> run_sources;       // the file of each run (join_records); empty for one record
    bool free_run = false;                      // no forcing column: u is 0 throughout (LoadOptions::free_run)
    bool has_phi() const { return !phi.empty(); }
    bool has_u() const { return !u.empty(); }
    std::size_t size() const { return t.size(); }
};

// Reads a CSV file, plain or gzip-compressed (recognised by its magic bytes, not its name).
MeasuredData load_measured(const std::string& path, const LoadOptions& options = {});
// Parses CSV text; `source` names it in messages.
MeasuredData parse_measured(std::string_view text, const std::string& source, const LoadOptions& options = {});
// "A:B" (Python-style, either side may be empty) into a row range; throws DataError.
void parse_row_range(const std::string& spec, long& begin, long& end);

// The bytes of a file, decompressed if it is gzip; throws DataError("PATH: ..."), also for what is no regular
// file (a directory, FIFO, device) and for more than kMaxInputBytes on disk or decompressed (input_file.hpp).
std::string read_data_file(const std::string& path);
bool is_gzip(std::string_view bytes);
// Decompresses gzip (one member or several concatenated) with zlib; refuses corrupt or truncated data and,
// as a gzip bomb, more than `max_bytes` of output (DataError naming `source`).
std::string gunzip(std::string_view bytes, const std::string& source, std::size_t max_bytes = std::size_t{1} << 30);
// A valid gzip member holding `text` uncompressed (stored blocks): what synth writes for FILE.csv.gz.
std::string gzip_stored(std::string_view text);

// Several runs of the same rig as one record with run boundaries: the same forcing column (phi or u) and
// the same sample step (within 1 %) in each; run k is shifted in time to start one step after run k-1 ends.
// Throws DataError naming the run that does not fit.
MeasuredData join_records(const std::vector<MeasuredData>& runs);

// Writes t,x and phi or u (and the meta as "# key: value" lines) in the MODEL.md layout.
void write_measured_csv(std::ostream& out, const MeasuredData& d);

}  // namespace impactlab::identify
