// What the browser build of the core cannot link, stubbed: the fits' least squares (Ceres) and gzip (zlib).
// Emscripten's own zlib is a port it would download, and Ceres has none; the page reads plain records and
// says so for gzip and for a fit. Also the stb implementations, which the desktop build takes from
// Debian's libstb.
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


namespace detail {
LsqSummary least_squares(std::vector<Knob>&, const ResidualFn&, const StepFn&, const LsqOptions&, Eigen::VectorXd&,
                         Eigen::MatrixXd*) {
    throw std::runtime_error("fitting needs Ceres, which the browser page lacks: use the desktop impactlab");
}
}  // namespace detail

}  // namespace impactlab::identify
