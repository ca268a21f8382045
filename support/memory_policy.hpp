#pragma once
// How the command-line tools ask the C library to manage freed memory.

namespace cli_support {

// Keeps large freed blocks in the process's heap instead of returning them to the system. The
// analyses build and free one neighbour tree after another, tens of megabytes each at 10^6 samples;
// by default glibc maps every such block afresh and unmaps it on free, so each tree paid for
// zeroing and faulting in its pages again (a third of `chaos lyapunov`'s time at 10^6 samples,
// docs/validation/performance-lyapunov.md). Freed blocks are reused rather than added to, so the
// peak stays that of the largest trees alive at once (there, 139 MB against 152 MB before); memory
// freed late in a run is returned when the process exits. A no-op outside glibc.
void keep_freed_memory_in_heap();

}  // namespace cli_support
