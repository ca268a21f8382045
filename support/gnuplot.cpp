#include "gnuplot.hpp"

#include <cerrno>

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include "safe_output.hpp"

namespace cli_support {

namespace {
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string plot_extension_refusal(const std::string& path, const std::string& option) {
  if (ends_with(path, ".png") || ends_with(path, ".svg")) return {};
  return option + ": the file must end in .png or .svg (got '" + path + "')";
}

namespace {

struct GnuplotRun {
  bool started = false;
  int status = -1;
  std::string image, messages;
};

// Runs gnuplot with `script` on its standard input and collects its standard output and error
// through pipes: no file is written on the way (gnuplot reports no failed write of its own, and a
// script file in /tmp would fail first on a full disk), so that the image's only write is the
// checked one of safe_output. Standard input is a socket so that a gnuplot that stops reading
// early gives an error here (MSG_NOSIGNAL), not a SIGPIPE.
GnuplotRun run_gnuplot(const std::string& script) {
  GnuplotRun run;
  int input[2], output[2], errors[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, input) != 0) return run;
  if (::pipe2(output, O_CLOEXEC) != 0) {
    ::close(input[0]), ::close(input[1]);
    return run;
  }
  if (::pipe2(errors, O_CLOEXEC) != 0) {
    ::close(input[0]), ::close(input[1]), ::close(output[0]), ::close(output[1]);
    return run;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, input[1], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, output[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, errors[1], STDERR_FILENO);
  char name[] = "gnuplot";
  char* argv[] = {name, nullptr};
  pid_t pid = -1;
  run.started = ::posix_spawnp(&pid, name, &actions, nullptr, argv, environ) == 0;
  posix_spawn_file_actions_destroy(&actions);
  ::close(input[1]), ::close(output[1]), ::close(errors[1]);
  if (!run.started) {
    ::close(input[0]), ::close(output[0]), ::close(errors[0]);
    return run;
  }
  std::size_t sent = 0;
  int to_child = input[0];
  if (script.empty()) ::close(to_child), to_child = -1;
  bool output_open = true, errors_open = true;
  char buffer[1 << 16];
  while (output_open || errors_open) {
    pollfd fds[3] = {{to_child, POLLOUT, 0}, {output_open ? output[0] : -1, POLLIN, 0}, {errors_open ? errors[0] : -1, POLLIN, 0}};
    if (::poll(fds, 3, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (to_child >= 0 && fds[0].revents) {
      const ssize_t n = ::send(to_child, script.data() + sent, script.size() - sent, MSG_NOSIGNAL | MSG_DONTWAIT);
      if (n > 0) sent += static_cast<std::size_t>(n);
      if ((n < 0 && errno != EAGAIN && errno != EINTR) || sent == script.size()) ::close(to_child), to_child = -1;
    }
    for (int k = 1; k <= 2; ++k) {
      if (!fds[k].revents) continue;
      const int fd = k == 1 ? output[0] : errors[0];
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      if (n > 0) (k == 1 ? run.image : run.messages).append(buffer, static_cast<std::size_t>(n));
      else if (n == 0 || errno != EINTR) (k == 1 ? output_open : errors_open) = false;
    }
  }
  if (to_child >= 0) ::close(to_child);
  ::close(output[0]), ::close(errors[0]);
  while (::waitpid(pid, &run.status, 0) < 0 && errno == EINTR) {
  }
  return run;
}

}  // namespace

void render(const std::string& script, const std::string& path) {
  std::string terminal;
  if (ends_with(path, ".png")) {
    terminal = "pngcairo size 1000,800 font 'sans,10'";
  } else if (ends_with(path, ".svg")) {
    terminal = "svg size 1000,800 dynamic font 'sans,10'";
  } else {
    throw PlotError(PlotError::Kind::bad_extension, plot_extension_refusal(path));
  }
  // Plain text everywhere: names such as not_saturated or crank_conrod are not subscripts. No
  // output file: the image comes back on gnuplot's standard output.
  const GnuplotRun run =
      run_gnuplot("set terminal " + terminal + "\nset termoption noenhanced\n" + script + "\nunset output\n");
  if (!run.started || run.status != 0 || run.image.empty()) {
    throw PlotError(PlotError::Kind::gnuplot_failed,
                    "--plot: gnuplot failed (is the gnuplot-nox package installed?)" +
                        (run.messages.empty() ? std::string() : ": " + run.messages));
  }
  safe_output::write_file(path, run.image);
}

}  // namespace cli_support
