#include "app/interrupt.h"

#include <csignal>
#include <unistd.h>

namespace tessera {
namespace {

std::atomic<bool>* g_cancel = nullptr;
volatile std::sig_atomic_t g_signals = 0;
struct sigaction g_old_int, g_old_term;

static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler stores to it");

void on_signal(int) {
  if (g_signals++ > 0) {
    static const char kMessage[] = "\ntessera: interrupted again: exiting now\n";
    (void)!::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    ::_exit(130);
  }
  static const char kMessage[] =
      "\ntessera: interrupted: finishing the tiles in flight, then writing what is done (again to quit now)\n";
  (void)!::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  if (g_cancel) g_cancel->store(true, std::memory_order_relaxed);
}

}  // namespace

InterruptHandler::InterruptHandler(std::atomic<bool>& cancel) {
  g_cancel = &cancel;
  g_signals = 0;
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, &g_old_int);
  sigaction(SIGTERM, &sa, &g_old_term);
}

InterruptHandler::~InterruptHandler() {
  sigaction(SIGINT, &g_old_int, nullptr);
  sigaction(SIGTERM, &g_old_term, nullptr);
  g_cancel = nullptr;
}

bool InterruptHandler::interrupted() const { return g_signals > 0; }

}  // namespace tessera
