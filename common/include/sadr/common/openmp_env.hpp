// SPDX-License-Identifier: MIT
/// \file openmp_env.hpp
/// Passive OpenMP waiting by default for the executables that run the fluid.
///
/// Why: libgomp's default lets idle team threads spin (busy-wait) at every
/// barrier. When the cores are shared (the SSA thread in `sadr --embedded`,
/// the ssa_service process, other jobs) the spinning threads steal the CPU from
/// the ones doing the work. Measured on the 2-core machine under load (1e4
/// particles, 2D SDPD, 2 OpenMP threads, embedded): 620 ms per coupling step
/// with the default, 60 ms with OMP_WAIT_POLICY=passive, 121 ms with one
/// thread (bench/results/README-coupled.md). libgomp reads the variable once
/// when it is loaded, so it has to be in the environment before the program
/// starts: if the user has not set OMP_WAIT_POLICY, we set it to `passive` and
/// re-execute the program once (Linux /proc/self/exe). Child processes inherit
/// it. Set OMP_WAIT_POLICY=active yourself on a dedicated machine.
#pragma once

namespace sadr {

/// Call first thing in main(). Returns only if nothing needs to change (or the
/// re-exec failed, which is reported on stderr and otherwise harmless).
void ensure_passive_openmp_wait(char** argv);

}  // namespace sadr
