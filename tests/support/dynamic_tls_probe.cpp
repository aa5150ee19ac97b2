// loom-dynamic-tls-probe <holder library> [--forget]
//
// Shows that LeakSanitizer, run with intercept_tls_get_addr=0 (the asan test preset; see
// docs/sanitizers.md for the runtime bug that option avoids), still treats memory referenced
// from dynamic TLS as reachable: blocks held only by a thread_local of a dlopen'd library, on
// the main thread and on a thread still running at exit, are not reported. With --forget the
// references are dropped and the blocks must be reported, so the clean run cannot pass because
// LeakSanitizer is blind. Registered as tests only in sanitizer builds (tests/support).
#include <dlfcn.h>
#include <pthread.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>

namespace {

using HoldFn = void (*)(std::size_t);
using SettleFn = void (*)(bool);

struct Holder {
    HoldFn hold = nullptr;
    SettleFn settle = nullptr;
    bool forget_after_hold = false;
    int ready[2] = {-1, -1};  // worker -> main: "holding"
};

void* worker(void* arg) {
    auto* holder = static_cast<Holder*>(arg);
    holder->hold(3000);
    holder->settle(!holder->forget_after_hold);
    char byte = 1;
    if (write(holder->ready[1], &byte, 1) != 1) return nullptr;
    for (;;) pause();  // still running when the process exits and LeakSanitizer looks
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || (argc == 3 && std::strcmp(argv[2], "--forget") != 0) || argc > 3) {
        std::fprintf(stderr, "usage: loom-dynamic-tls-probe <holder library> [--forget]\n");
        return 2;
    }
    void* library = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
        std::fprintf(stderr, "loom-dynamic-tls-probe: %s\n", dlerror());
        return 1;
    }
    static Holder holder;
    holder.hold = reinterpret_cast<HoldFn>(dlsym(library, "loom_tls_hold"));
    holder.settle = reinterpret_cast<SettleFn>(dlsym(library, "loom_tls_settle"));
    holder.forget_after_hold = argc == 3;
    if (holder.hold == nullptr || holder.settle == nullptr || pipe(holder.ready) != 0) {
        std::fprintf(stderr, "loom-dynamic-tls-probe: %s has no loom_tls_hold/loom_tls_settle\n", argv[1]);
        return 1;
    }
    holder.hold(5000);
    holder.settle(!holder.forget_after_hold);
    pthread_t thread;
    if (pthread_create(&thread, nullptr, worker, &holder) != 0) return 1;
    char byte = 0;
    if (read(holder.ready[0], &byte, 1) != 1) return 1;
    std::printf("loom-dynamic-tls-probe: blocks %s\n", holder.forget_after_hold ? "forgotten" : "held in dynamic TLS");
    std::fflush(stdout);
    return 0;  // exits with the worker still running; LeakSanitizer checks at exit
}
