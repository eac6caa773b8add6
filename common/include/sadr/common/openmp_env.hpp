// SPDX-License-Identifier: MIT
/// \file openmp_env.hpp
/// Bounded OpenMP spinning by default for the executables that run OpenMP loops.
///
/// libgomp's default (OMP_WAIT_POLICY unset) lets an idle team thread spin for
/// 300000 iterations (~17 ms here) at every barrier and between parallel
/// regions; `active` spins for ever. When the cores are shared (the SSA in
/// `sadr --embedded`, the ssa_service process, other jobs) those spinning
/// threads take the CPU from the threads doing the work. Measured on the 2-core
/// machine under load (1e4 particles, 2D SDPD, 2 threads, embedded): 620 ms per
/// coupling step with `active`, 60 ms passive, 121 ms with one thread
/// (bench/results/README-coupled.md). Fully passive waits (futex sleep at every
/// barrier) cost the other way: the fluid step has several short parallel
/// regions, and waking a sleeping thread for each made 1 -> 2 threads only
/// 1.3-1.4x (2D 1e4, quiet machine) against 1.68-1.74x with a short spin.
///
/// So, if the user set neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT, we set
/// OMP_WAIT_POLICY=passive and GOMP_SPINCOUNT=kBoundedSpinCount: a thread spins
/// ~0.5 ms (measured 57 ns per libgomp spin iteration on this machine) and then
/// sleeps. That covers the gaps between the regions of one step and bounds the
/// CPU an idle service burns after its last region. libgomp itself drops the
/// spinning to zero (passive) when the process has more OpenMP threads than
/// CPUs (e.g. the fluid and SSA teams of `--embedded` on 2 cores).
///
/// libgomp reads both variables once when it is loaded, so they must be in the
/// environment before the program starts: we set them and re-execute the
/// program once (Linux /proc/self/exe). Child processes inherit them. Set
/// either variable yourself to choose (e.g. OMP_WAIT_POLICY=active on a
/// dedicated machine; OMP_WAIT_POLICY=passive alone for no spinning at all).
#pragma once

namespace sadr {

/// GOMP_SPINCOUNT set by ensure_bounded_openmp_wait() (libgomp spin iterations).
inline constexpr const char* kBoundedSpinCount = "10000";

/// Call first thing in main(). Returns only if nothing needs to change (or the
/// re-exec failed, which is reported on stderr and otherwise harmless).
void ensure_bounded_openmp_wait(char** argv);

}  // namespace sadr
