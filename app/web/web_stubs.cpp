// What the browser build of the core cannot link, stubbed: the fits' least squares (Ceres), gzip (zlib)
// and the measured-data loader (emscripten 3.1.6's libc++ has no floating-point std::from_chars).
// Emscripten's own zlib is a port it would download, and Ceres has none; a page cannot load a measured run
// from disk anyway (it says so). Also the stb implementations, which the desktop build takes
// from Debian's libstb.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

#include <stdexcept>
#include <string>

#include "identify/internal.hpp"
#include "impactlab/identify_data.hpp"

namespace impactlab::identify {

bool is_gzip(std::string_view bytes) {
    return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f && static_cast<unsigned char>(bytes[1]) == 0x8b;
}
std::string gunzip(std::string_view, const std::string& source, std::size_t) {
    throw DataError(source + ": gzip data cannot be read in the browser (use the desktop impactlab)");
}
std::string gzip_stored(std::string_view) {
    throw DataError("gzip cannot be written in the browser (use the desktop impactlab)");
}

MeasuredData load_measured(const std::string& path, const LoadOptions&) { return parse_measured({}, path, {}); }
MeasuredData parse_measured(std::string_view, const std::string& source, const LoadOptions&) {
    throw DataError(source + ": measured data cannot be loaded in the browser (use the desktop impactlab)");
}
std::string read_data_file(const std::string& path) { return gunzip({}, path, 0); }
MeasuredData join_records(const std::vector<MeasuredData>&) { return parse_measured({}, "records", {}); }
void write_measured_csv(std::ostream&, const MeasuredData&) { gzip_stored({}); }

namespace detail {
LsqSummary least_squares(std::vector<Knob>&, const ResidualFn&, const StepFn&, const LsqOptions&, Eigen::VectorXd&,
                         Eigen::MatrixXd*) {
    throw std::runtime_error("fitting needs Ceres, which the browser page lacks: use the desktop impactlab");
}
}  // namespace detail

}  // namespace impactlab::identify
