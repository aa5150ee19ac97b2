// A library loaded with dlopen by loom-dynamic-tls-probe (dynamic_tls_probe.cpp): its
// thread_local lives in dynamic TLS, the kind Mesa's drivers and the Vulkan layers use, which
// glibc allocates per thread on first use and reaches only through the thread's DTV.
#include <cstdlib>

namespace {
thread_local void* held_block = nullptr;
}

// Allocates `size` bytes whose only reference is this thread's copy of held_block.
extern "C" __attribute__((visibility("default"))) void loom_tls_hold(std::size_t size) {
    held_block = std::malloc(size);
}

// With keep false, drops that reference without freeing the block: a real leak. Either way it
// reaches the thread_local the same way, so that both runs leave the same traces on the stack
// and in registers, and only the reference in TLS differs.
extern "C" __attribute__((visibility("default"))) void loom_tls_settle(bool keep) {
    void* volatile* slot = &held_block;
    *slot = keep ? *slot : nullptr;
}
