#include "base/interrupt.h"

#include <signal.h>

namespace xshade {
namespace {

constexpr int kCaught[] = {SIGINT, SIGTERM, SIGHUP};

volatile sig_atomic_t g_signal = 0;

void on_interrupt(int signal) {
  if (g_signal != 0) {
    // Asked twice: stop now. Only async-signal-safe calls here.
    struct sigaction fallback {};
    fallback.sa_handler = SIG_DFL;
    sigaction(signal, &fallback, nullptr);
    raise(signal);
    return;
  }
  g_signal = signal;
}

// A signal ignored when the process started (nohup's SIGHUP, SIGINT of a shell's background
// job) stays ignored.
void set_handler(void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: a wait in progress returns, and its loop sees the signal
  for (int signal : kCaught) {
    struct sigaction before {};
    if (sigaction(signal, nullptr, &before) == 0 && before.sa_handler == SIG_IGN) continue;
    sigaction(signal, &action, nullptr);
  }
}

}  // namespace

void catch_interrupts() { set_handler(on_interrupt); }

void stop_catching_interrupts() {
  set_handler(SIG_DFL);
  g_signal = 0;
}

int interrupt_signal() { return g_signal; }

}  // namespace xshade
