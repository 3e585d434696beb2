// Files written whole or not at all: the bytes go to a hidden partial file beside the target and are renamed
// over it once complete, so a failed run leaves an old file as it was (the CLI's outputs, PNGs, fit reports).
// Several files that belong together (a CSV and its PNG, a fit report) are committed as a unit by an
// OutputGroup: all are written first, and renamed into place only when every one of them succeeded.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace impactlab {

// ".NAME.partial-PID" in the directory of `path` (the PID keeps two processes' partial files apart). Once
// remove_partials_on_signal was called, the name is remembered until commit_partial or discard_partial.
// The first call for a directory also removes the partial files there whose process is gone (a run killed by
// SIGKILL or a power cut leaves them; the PID in the name says whose they were).
std::string partial_path(const std::string& path);
// Renames `partial` over `path`; if that fails, removes `partial` and throws std::runtime_error naming `path`.
// While an OutputGroup is open on this thread, the partial is staged in it instead, renamed by its commit().
void commit_partial(const std::string& partial, const std::string& path);
// Removes a partial file that will not be committed (no error if it is gone).
void discard_partial(const std::string& partial);
// Writes `bytes` to `path` whole: into its partial file, every write and the close checked, then
// commit_partial. Throws std::runtime_error naming `path` and the system's reason (no space left on device).
void write_file_whole(const std::string& path, std::string_view bytes);
// Removes, in `dir`, every ".NAME.partial-PID" (file or folder) whose process PID no longer exists; returns
// how many. partial_path calls it once per directory.
int remove_stale_partials(const std::string& dir);

// Outputs committed as a unit. While a group is open on a thread, commit_partial stages finished partial files
// in it; the outermost group's commit() renames them all into place, and if one rename fails puts the old
// files back. A group that ends uncommitted (an exception, a failed write) removes the partials staged in it,
// so the old set stays whole. Inner groups join the outermost one.
class OutputGroup {
public:
    OutputGroup();
    ~OutputGroup();
    OutputGroup(const OutputGroup&) = delete;
    OutputGroup& operator=(const OutputGroup&) = delete;
    // Outermost group: renames every staged file into place (throws std::runtime_error naming the one that
    // failed, the old files restored); inner group: nothing, the outermost decides.
    void commit();
    // Removes every staged partial file (outermost group; what the destructor does uncommitted).
    void discard();

private:
    bool outermost_;
};

// Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGPIPE that remove every partial file not yet committed
// or discarded, then let the signal end the process as it would have (exit status 128 + signal in a shell).
// A closed pipe on stdout or stderr (`impactlab scan ... | head`) thus ends a run like SIGINT. A signal the
// process ignores stays ignored. For programs whose only reaction to these signals is to stop (the CLI);
// call once, from main.
void remove_partials_on_signal();

}  // namespace impactlab
