#include "app/terminal/interrupt.h"

#include <unistd.h>

#include <csignal>

#include "imageio/file_output.h"

namespace tessera {
namespace {

std::atomic<std::atomic<bool>*> g_cancel{nullptr};
volatile std::sig_atomic_t g_signals = 0;
volatile std::sig_atomic_t g_quiet = 0;

static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler stores to it");
static_assert(std::atomic<std::atomic<bool>*>::is_always_lock_free, "the signal handler loads it");

void on_signal(int) {
  if (g_signals++ > 0) {
    static const char kMessage[] = "\ntessera: interrupted again: exiting now\n";
    if (!g_quiet) (void)!::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
    remove_temporary_files();  // a write in progress leaves nothing behind
    ::_exit(130);
  }
  static const char kMessage[] =
      "\ntessera: interrupted: finishing the work in flight, then writing what is done (again to quit now)\n";
  if (!g_quiet) (void)!::write(STDERR_FILENO, kMessage, sizeof kMessage - 1);
  if (std::atomic<bool>* cancel = g_cancel.load()) cancel->store(true, std::memory_order_relaxed);
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  // Unix etiquette: a SIGINT the parent ignores (a background job, nohup) stays ignored, so
  // a Ctrl-C at the terminal does not reach it.
  struct sigaction old {};
  if (sigaction(SIGINT, nullptr, &old) == 0 && old.sa_handler != SIG_IGN) sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

void quiet_interrupt_messages() { g_quiet = 1; }

InterruptHandler::InterruptHandler(std::atomic<bool>& cancel) {
  g_cancel.store(&cancel);
  if (g_signals > 0) cancel.store(true);  // the signal came before the work began
}

InterruptHandler::~InterruptHandler() { g_cancel.store(nullptr); }

bool InterruptHandler::interrupted() const { return g_signals > 0; }

}  // namespace tessera
