#pragma once
// Number of malloc/calloc/realloc calls in the process so far.
unsigned long allocation_count();
