// SPDX-License-Identifier: Apache-2.0
#pragma once
// Counts calls to the global operator new of the executable that links
// gnssemu_alloc_counter (it replaces operator new/delete). Used by tests and
// benchmarks that prove a hot path does not allocate after warm-up.

namespace gnssemu::support {

/// Global operator new calls so far in this process.
long allocation_count() noexcept;

}  // namespace gnssemu::support
