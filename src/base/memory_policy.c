/* The C library's policy for large arrays (issue 32: the system time of
 * the 1e6-dof square).
 *
 * glibc hands out every block above its mmap threshold (128 KiB at first,
 * raised as such blocks are freed, at most 32 MiB) as pages of its own
 * and returns them to the kernel when the block is freed; the next large
 * array then gets fresh pages, which the kernel must clear at the first
 * touch of each (a page fault per 4 KiB). A run allocates and frees its
 * large arrays in phases (the deck's lines, the matrix pattern, CHOLMOD's
 * ordering and analysis, the factor), so most of its page faults were of
 * memory it had held and freed a moment before: on the 1e6-dof square
 * 583 558 minor faults for a peak of 1.94 GB (the kernel's clearing and
 * mapping of pages was most of the run's 1.1 to 1.4 s of system time).
 *
 * Here every block comes from the heap (M_MMAP_MAX = 0) and the heap is
 * not given back while the process runs (M_TRIM_THRESHOLD at its
 * largest), so that memory once touched is reused by the next arrays.
 * The peak is the same to within the heap's fragmentation (measured:
 * docs/benchmark.md); everything is returned when the process ends.
 *
 * A constructor, so that it holds from the first allocation of every
 * program linked with it (cfe2d, the unit tests) without a call in each;
 * other C libraries (and the sanitizers' allocators) are left alone. */
#include <limits.h>   /* (glibc's features.h: __GLIBC__) */
#ifdef __GLIBC__
#include <malloc.h>
#endif

__attribute__((constructor)) static void cfe_memory_policy(void)
{
#if defined(__GLIBC__) && defined(M_MMAP_MAX) && defined(M_TRIM_THRESHOLD)
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}
