// Runs a command as a user does, in a child process of its own, and measures it: wall
// seconds and the child's peak resident memory (getrusage's ru_maxrss, through wait4),
// with its standard output and error kept in a file.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace dynrad::bench {

struct ChildRun {
  int exit_code = -1;
  double seconds = 0;
  double peak_mib = 0;  // resident
  std::string output;   // standard output and error
};

// Runs `argv` (argv[0] found on PATH or given as a path) with its output going to
// `log`, and waits for it. Exits the benchmark with a message if it cannot start.
inline ChildRun run_child(const std::vector<std::string>& argv, const std::string& log) {
  ChildRun run;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    std::perror("fork");
    std::exit(1);
  }
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    std::perror(args[0]);
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;  // KiB on Linux
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

// The same, and the benchmark stops (printing the command's output) if it fails.
inline ChildRun run_or_exit(const std::vector<std::string>& argv, const std::string& log) {
  ChildRun run = run_child(argv, log);
  if (run.exit_code != 0) {
    std::string command;
    for (const std::string& a : argv) command += a + " ";
    std::fprintf(stderr, "failed (exit %d): %s\n%s\n", run.exit_code, command.c_str(), run.output.c_str());
    std::exit(1);
  }
  return run;
}

}  // namespace dynrad::bench
