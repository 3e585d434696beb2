// The UI thread's end of the command ring: every command to the simulation thread goes through send().
// A command the full ring refuses is held back and sent again at the next frame (flush()), in order, so
// nothing is lost silently. A slider dragged while the simulation thread is busy sends a new value every
// frame: a held value of the same setting gives way to it (it goes to the back of the line, where the user
// set it), so the backlog does not grow and the last value always lands. Only past kBacklogCapacity held
// commands is one given up, and counted (lost()). GL-free; UI thread only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>

#include "sim/sim_messages.hpp"

namespace impactlab::gui {

class SimThread;

class CommandLink {
public:
    static constexpr std::size_t kBacklogCapacity = 64;

    // The thread the commands go to (null: none yet, every command is held).
    void attach(SimThread* sim) { sim_ = sim; }
    // Sends `c`, or holds it back behind the commands already held (their order is kept). False only when
    // it is given up (the backlog is full): the caller may tell the user.
    bool send(const SimCommand& c);
    // Once a frame: the held commands, oldest first, until the ring refuses one. True when none is left.
    bool flush();

    std::size_t waiting() const { return backlog_.size(); }   // held now
    std::uint64_t deferred() const { return deferred_; }       // could not go straight in, since the start
    std::uint64_t lost() const { return lost_; }               // given up, since the start

private:
    SimThread* sim_ = nullptr;
    std::deque<SimCommand> backlog_;
    std::uint64_t deferred_ = 0, lost_ = 0;
};

// Whether `later` makes `earlier` pointless: a new value for the same setting (omega, xI, speed, pause,
// one parameter, the section phase, where the mouse holds or puts the cart). What lies between them in the
// line (a reset, a model switch, a ramp) leaves the setting to the later value, so the earlier is dropped.
bool supersedes(const SimCommand& later, const SimCommand& earlier);

}  // namespace impactlab::gui
