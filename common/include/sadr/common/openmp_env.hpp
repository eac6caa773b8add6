// SPDX-License-Identifier: MIT
/// \file openmp_env.hpp
/// Passive OpenMP waiting by default for the executables that run OpenMP loops.
///
/// libgomp's default (OMP_WAIT_POLICY unset) lets an idle team thread spin for
/// 300000 iterations (~17 ms here, 57 ns per iteration) at every barrier and
/// between parallel regions; `active` spins for ever. In a coupled run only one
/// service computes at a time, and the other's spinning threads take the CPU
/// from it (and from other jobs). Measured on the 2-core machine under load
/// (1e4 particles, 2D SDPD, 2 threads, embedded): 620 ms per coupling step with
/// `active`, 60 ms passive, 121 ms with one thread
/// (bench/results/README-coupled.md). A bounded spin (GOMP_SPINCOUNT=10000,
/// ~0.5 ms) was tried as the default in round 4 and dropped: in process mode
/// the fluid's spinning tail delayed the SSA (transfer 2.2-2.4 vs 0.7-0.9 ms
/// per step at 1e4), and since the bulk-fluid SDPD sub-step (the benchmark's) runs in two parallel
/// regions with point-to-point slab ordering, passive waits cost its 1 -> 2 thread scaling nothing
/// measurable (bench/results/nsm_sdpd_speed_interleaved.md).
///
/// libgomp reads the variables once when it is loaded, so they must be in the
/// environment before the program starts: if the user set neither
/// OMP_WAIT_POLICY nor GOMP_SPINCOUNT, we set OMP_WAIT_POLICY=passive and
/// re-execute the program once (Linux /proc/self/exe). Child processes inherit
/// it. Set either variable yourself to choose (e.g. OMP_WAIT_POLICY=active on a
/// dedicated machine running the fluid alone).
#pragma once

namespace sadr {

/// Call first thing in main(). Returns only if nothing needs to change (or the
/// re-exec failed, which is reported on stderr and otherwise harmless).
void ensure_passive_openmp_wait(char** argv);

/// A service's OpenMP thread count from the environment variable `name`
/// (SADR_FLUID_THREADS, SADR_SSA_THREADS: set by the orchestrator's --fluid-threads /
/// --ssa-threads, so the two services get different counts although both inherit one
/// environment and, embedded, share one process). 0 if unset or empty (OpenMP's default:
/// OMP_NUM_THREADS or all cores). Throws InvalidArgument naming the variable and the
/// allowed range (1..4096) for anything else.
int service_threads_from_env(const char* name);

}  // namespace sadr
