#pragma once
// Large buffers: a job's text, its packed holes, the holes of a drilling operation, the safety
// check's hole log. Each is reserved once at the size it will reach (growing a vector by
// doubling copies it and touches twice its memory), and backed by huge pages where the system
// offers them: filling 100 MB of 4 KiB pages costs 25,000 page faults, and on a virtual machine
// each fault can cost as much as formatting fifty lines of NC text (bench/README.md).
#include <cstddef>
#include <vector>

namespace camgen {

// Asks the system to back the whole 2 MiB pages inside [data, data + bytes) with huge pages
// (Linux: madvise MADV_HUGEPAGE, for transparent huge pages in their "madvise" mode; nothing
// elsewhere, and nothing for less than large_buffer_bytes). Advice only: pages not touched yet
// take no memory, and a system without transparent huge pages ignores it.
void advise_huge_pages(const void* data, std::size_t bytes);

// Buffers below this size (bytes) get no advice: a few hundred page faults at most.
inline constexpr std::size_t large_buffer_bytes = std::size_t{4} << 20;

// v.reserve(n), with the room reserved advised as above.
template <class T>
void reserve_large(std::vector<T>& v, std::size_t n) {
    if (n <= v.capacity()) return;
    v.reserve(n);
    advise_huge_pages(v.data(), v.capacity() * sizeof(T));
}

}  // namespace camgen
