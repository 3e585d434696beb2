// Headless benchmarks of the visualiser's machinery (not tests): the ring buffer's throughput and the
// simulation's real-time factor. The plotting benchmark needs a window and lives in app.cpp. GL-free.
#pragma once

namespace impactlab::gui {

// Two threads, 50 million 64-byte samples through SpscRing<SimMsg>; prints samples/s. Returns 0.
int bench_ring();
// A1H and A1C at omega = 18 rad/s from the left well: the bare simulator and the GUI engine (samples at
// 1 ms with energy and bumper force, into a ring drained by a second thread); prints real-time factors.
int bench_sim();

}  // namespace impactlab::gui
