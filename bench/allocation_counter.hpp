// Counts calls of the global operator new in this executable (allocation_counter.cpp replaces
// it), so that the benchmark can report allocations per call and the no-allocation tests can
// assert none (they compile allocation_counter.cpp in too).
#pragma once

namespace bench {
long allocation_count();
}
