// The builder command's work in the executable that holds the server (plantarch-builder, and
// the tests): serve the project builder (builder/server/server.h) until SIGINT or SIGTERM
// (apps/builder.cpp parses the options; the plantarch command hands its command line to this
// executable, so it loads none of the server's libraries itself).

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cstdio>
#include <thread>

#include "builder/server/server.h"
#include "builder_command.h"
#include "plantarch/Error.h"

extern char** environ;

namespace plantarch::cli {

namespace {

// Opens `url` in the desktop's browser (xdg-open), without waiting for it. xdg-open's own
// output is dropped (on a machine without a browser it lists every one it tried); when it
// fails, one line says so.
void openBrowser(const std::string& url) {
    posix_spawn_file_actions_t quiet;
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    const char* argv[] = {"xdg-open", url.c_str(), nullptr};
    const int spawned =
        posix_spawnp(&pid, "xdg-open", &quiet, nullptr, const_cast<char**>(argv), environ);
    posix_spawn_file_actions_destroy(&quiet);
    if (spawned != 0) {
        std::fprintf(stderr, "plantarch: note: could not start xdg-open; open %s yourself\n",
                     url.c_str());
        return;
    }
    std::thread([pid, url] {  // no zombie left
        int status = 0;
        if (waitpid(pid, &status, 0) == pid && !(WIFEXITED(status) && WEXITSTATUS(status) == 0))
            std::fprintf(stderr,
                         "plantarch: note: xdg-open found no web browser; open %s yourself\n",
                         url.c_str());
    })
        .detach();
}

}  // namespace

int runBuilderCommand(const BuilderArgs& a, const GlobalOptions& global) {
    // SIGINT and SIGTERM stop the server (its builds cancelled, its files whole): they are
    // blocked in every thread and taken by one that waits for them.
    sigset_t stopSignals;
    sigemptyset(&stopSignals);
    sigaddset(&stopSignals, SIGINT);
    sigaddset(&stopSignals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &stopSignals, nullptr);

    builder::ServerOptions o;
    o.host = a.host;
    o.port = a.port;
    o.output = a.output;
    o.maxTriangles = global.maxTriangles;
    builder::Server server(o);
    const int port = server.bind();
    const bool local = a.host == "127.0.0.1" || a.host == "localhost";
    if (!local)
        std::fprintf(stderr,
                     "plantarch: warning: --host %s: anyone who can reach this machine on port %d "
                     "can build scenes and write files under %s\n",
                     a.host.c_str(), port, server.outputFolder().c_str());
    const std::string url =
        "http://" + std::string(local ? "127.0.0.1" : a.host) + ":" + std::to_string(port) + "/";
    std::printf("plantarch builder: %s (output folder %s); Ctrl-C stops it\n", url.c_str(),
                server.outputFolder().c_str());
    std::fflush(stdout);
    std::thread stopper([&] {
        int signal = 0;
        sigwait(&stopSignals, &signal);
        server.stop();
    });
    if (a.open) openBrowser(url);
    server.serve();
    // serve() returned: a signal stopped it, or the listening socket failed; make sure the
    // waiting thread ends too.
    pthread_kill(stopper.native_handle(), SIGTERM);
    stopper.join();
    std::printf("plantarch builder: stopped\n");
    return 0;
}

}  // namespace plantarch::cli
