#include "command_link.hpp"

#include <algorithm>
#include <cstring>

#include "sim/sim_thread.hpp"

namespace impactlab::gui {

bool supersedes(const SimCommand& later, const SimCommand& earlier) {
    if (later.kind != earlier.kind) return false;
    switch (later.kind) {
        case CmdKind::SetOmega:
        case CmdKind::SetXI:
        case CmdKind::SetSpeed:
        case CmdKind::SetPaused:
        case CmdKind::SetState:
        case CmdKind::Hold:
        case CmdKind::SetSectionPhase:
            return true;
        case CmdKind::SetParam:   // the same key
            return std::strncmp(later.model, earlier.model, sizeof later.model) == 0;
        default:
            return false;   // a step, a reset, a model switch or a restart each counts
    }
}

bool CommandLink::send(const SimCommand& c) {
    if (backlog_.empty() && sim_ && sim_->send(c)) return true;
    ++deferred_;
    const auto same = std::find_if(backlog_.begin(), backlog_.end(), [&](const SimCommand& h) { return supersedes(c, h); });
    if (same != backlog_.end()) {
        backlog_.erase(same);   // at most one: each value held gave way to the next
        backlog_.push_back(c);
        return true;
    }
    if (backlog_.size() >= kBacklogCapacity) {
        ++lost_;
        return false;
    }
    backlog_.push_back(c);
    return true;
}

bool CommandLink::flush() {
    while (!backlog_.empty() && sim_ && sim_->resend(backlog_.front())) backlog_.pop_front();
    return backlog_.empty();
}

}  // namespace impactlab::gui
