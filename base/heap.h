// How the process's heap gives memory back. A compile frees its whole tree when it ends, and
// glibc returns the top of its heap to the system whenever more than 128 KiB of it is free
// (M_TRIM_THRESHOLD): the next compile then asks for the same pages again (a brk and the page
// faults behind it, twice or three times a compile). xshade compiles dozens of variants and
// renders dozens of images in one process, each about the size of the last. glibc raises both
// thresholds by itself only after freeing a mapped buffer, which a process that only compiles
// never does.
#pragma once

namespace xshade {

// Called first thing in main: up to 8 MiB of freed memory stays in the heap for the next compile
// or image (a compile's tree and tables take one or two), and buffers below 4 MiB (a 512 x 512
// RGBA float image is 4 MiB) come from the heap rather than from a mapping of their own, made
// and unmapped, page faults and all, for every image. Measured on a warm `xshade run` of the
// fixed scenes (2 cores): 4.2 s -> 3.7 s wall, 2.1 s -> 1.6 s in the kernel, the largest
// process 210 -> 222 MB. With 32 MiB and 64 MiB (glibc's own ceiling for the thresholds it
// moves by itself): 3.3 s, but 278 MB. Does nothing where the C library is not glibc.
void keep_freed_heap();

}  // namespace xshade
