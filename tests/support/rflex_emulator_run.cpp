// rflex_emulator_run: runs a command against an emulated rFLEX controller, for CLI tests.
//
//   rflex_emulator_run --link PATH [--silent] [--garbage] [--interrupt-after S] -- COMMAND...
//
// Starts the emulator on a pseudo-terminal, points the symlink PATH at it (so a config file
// can name a fixed device), runs COMMAND (with --interrupt-after, sending it SIGINT S seconds
// after its first axis command: the base is driving then, however long COMMAND took to start,
// as under a sanitizer on a busy machine), then prints the emulated robot's final state to stderr
// ("emulator: pose X Y THETA, speed V, axis commands N, brake on|off") and exits with COMMAND's
// exit code.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "robots/rflex/rflex_emulator.h"

int main(int argc, char** argv) {
  std::string link;
  bool silent = false, garbage = false;
  double interrupt_after = -1.0;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--link" && i + 1 < argc) {
      link = argv[++i];
    } else if (a == "--silent") {
      silent = true;
    } else if (a == "--garbage") {
      garbage = true;
    } else if (a == "--interrupt-after" && i + 1 < argc) {
      interrupt_after = std::stod(argv[++i]);
    } else if (a == "--") {
      ++i;
      break;
    } else {
      std::fprintf(stderr, "rflex_emulator_run: unknown argument '%s'\n", a.c_str());
      return 64;
    }
  }
  if (link.empty() || i >= argc) {
    std::fprintf(stderr,
                 "usage: rflex_emulator_run --link PATH [--silent] [--garbage] -- COMMAND...\n");
    return 64;
  }
  coopmap::RflexEmulator emulator;
  emulator.setSilent(silent);
  emulator.setGarbage(garbage);
  std::error_code ec;
  std::filesystem::remove(link, ec);
  std::filesystem::create_symlink(emulator.device(), link, ec);
  if (ec) {
    std::fprintf(stderr, "rflex_emulator_run: cannot link %s: %s\n", link.c_str(),
                 ec.message().c_str());
    return 64;
  }

  std::fflush(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    std::perror("rflex_emulator_run: fork");
    return 64;
  }
  if (pid == 0) {
    ::execv(argv[i], argv + i);
    std::fprintf(stderr, "rflex_emulator_run: cannot run %s: %s\n", argv[i], std::strerror(errno));
    ::_exit(127);
  }
  int status = 0;
  bool exited = false;
  if (interrupt_after >= 0.0) {
    // Until the first axis command (at most 60 s), unless COMMAND ends first.
    for (int k = 0; k < 6000 && emulator.counters().axis_commands == 0; ++k) {
      const pid_t done = ::waitpid(pid, &status, WNOHANG);
      if (done == pid) {
        exited = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (!exited) {
      std::this_thread::sleep_for(std::chrono::duration<double>(interrupt_after));
      ::kill(pid, SIGINT);
    }
  }
  while (!exited && ::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  // Let the base come to rest after the last command.
  for (int k = 0; k < 200 && std::abs(emulator.linearVelocity()) > 0.0; ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const coopmap::Pose2 p = emulator.pose();
  const coopmap::RflexEmulatorCounters c = emulator.counters();
  std::fprintf(stderr, "emulator: pose %.3f %.3f %.3f, speed %.3f, axis commands %llu, brake %s\n",
               p.x, p.y, p.theta, emulator.linearVelocity(),
               static_cast<unsigned long long>(c.axis_commands), c.brake_on ? "on" : "off");
  std::filesystem::remove(link, ec);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}
