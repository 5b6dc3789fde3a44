// Counts calls of the global operator new in this executable (allocation_counter.cpp replaces
// it), so that the benchmark can report allocations per call.
#pragma once

namespace bench {
long allocation_count();
}
