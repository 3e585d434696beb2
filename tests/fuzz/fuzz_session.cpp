// libFuzzer: the visualiser's session files. Every input is a Session or a SessionError naming the file, and
// a session that loads writes a file that loads again.
#include <cstddef>
#include <cstdint>
#include <string>

#include "../../app/gui/files/session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace impactlab::gui;
    const std::string text(reinterpret_cast<const char*>(data), size);
    Session s;
    try {
        s = parse_session(text, Session{}, "fuzz.json");
    } catch (const SessionError&) {
        return 0;
    }
    try {
        (void)parse_session(session_text(s), Session{}, "again.json");
    } catch (const SessionError&) {
        __builtin_trap();   // what was accepted must be written so that it is accepted again
    }
    return 0;
}
