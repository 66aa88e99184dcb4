#include "base/subprocess.h"

#include <signal.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

namespace xshade {
namespace {

using namespace std::chrono_literals;

// Polls the child until it ends.
void finish(ChildProcess& child) {
  while (!child.poll()) wait_for_any({&child}, 100ms);
}

ChildProcess shell(const std::string& script, std::vector<std::string> environment = {},
                   ChildProcess::Clock::duration limit = 60s) {
  auto child = ChildProcess::start({"/bin/sh", "-c", script}, environment, limit);
  EXPECT_TRUE(child) << child.error().to_string();
  return std::move(*child);
}

TEST(ChildProcess, CollectsOutputAndErrorAndTheExitCode) {
  ChildProcess child = shell("echo out; echo err >&2; exit 3");
  finish(child);
  EXPECT_EQ(child.exit_status().code, 3);
  EXPECT_EQ(child.exit_status().signal, 0);
  EXPECT_FALSE(child.exit_status().timed_out);
  EXPECT_EQ(child.output(), "out\nerr\n");
}

TEST(ChildProcess, KeepsTheLastStatusLine) {
  ChildProcess child = shell("echo 'in pass one' >&3; echo 'in pass two' >&3; printf 'half a line' >&3");
  finish(child);
  EXPECT_EQ(child.last_status(), "in pass two");
  EXPECT_EQ(child.exit_status().code, 0);
}

TEST(ChildProcess, NamesTheSignalThatEndedIt) {
  ChildProcess child = shell("kill -SEGV $$");
  finish(child);
  EXPECT_EQ(child.exit_status().signal, SIGSEGV);
  EXPECT_EQ(describe_signal(child.exit_status().signal), "SIGSEGV (segmentation fault)");
}

TEST(ChildProcess, IsKilledAtItsDeadline) {
  ChildProcess child = shell("echo 'in pass slow' >&3; sleep 30", {}, 200ms);
  finish(child);
  EXPECT_TRUE(child.exit_status().timed_out);
  EXPECT_EQ(child.exit_status().signal, SIGKILL);
  EXPECT_EQ(child.last_status(), "in pass slow");
}

// A child that serves requests: each read from its input, answered on its output and with a
// "done" status line; the parent takes output and status lines request by request, and each
// request has a deadline of its own.
TEST(ChildProcess, ServesRequestsEachWithItsOutputStatusAndDeadline) {
  ChildProcess child = shell(
      "while read request; do echo \"answer $request\"; echo \"done $request\" >&3; "
      "[ \"$request\" = slow ] && sleep 30; done",
      {}, 60s);
  for (const std::string request : {"one", "two"}) {
    ASSERT_TRUE(child.send(request));
    std::vector<std::string> lines;
    while (lines.empty()) {
      wait_for_any({&child}, 100ms);
      ASSERT_FALSE(child.poll()) << child.output();
      lines = child.take_status_lines();
    }
    EXPECT_EQ(lines, std::vector<std::string>{"done " + request});
    EXPECT_EQ(child.take_output(), "answer " + request + "\n");
  }
  // The third request's deadline, not the child's start, ends it.
  child.set_deadline(ChildProcess::Clock::now() + 300ms);
  ASSERT_TRUE(child.send("slow"));
  finish(child);
  EXPECT_TRUE(child.exit_status().timed_out);
  EXPECT_EQ(child.take_output(), "answer slow\n");
  EXPECT_FALSE(child.send("after")) << "an ended child takes no request";
}

// A child forked to run a function: its output and code like a program's; an exception ends it
// (exit 3) rather than unwinding into our frames; and it is refused while we run a thread.
TEST(ChildProcess, AForkedChildRunsItsFunctionAndNothingElseOfOurs) {
  remember_startup_threads();
  auto child = ChildProcess::fork(
      [] {
        std::printf("forked %s\n", std::getenv("XSHADE_FORK_TEST"));
        return 7;
      },
      {"XSHADE_FORK_TEST=yes"}, 60s);
  ASSERT_TRUE(child) << child.error().to_string();
  finish(*child);
  EXPECT_EQ(child->exit_status().code, 7);
  EXPECT_EQ(child->output(), "forked yes\n");

  auto throwing = ChildProcess::fork([]() -> int { throw std::runtime_error("no"); }, {}, 60s);
  ASSERT_TRUE(throwing);
  finish(*throwing);
  EXPECT_EQ(throwing->exit_status().code, 3);

  std::promise<void> release;
  std::thread busy([&] { release.get_future().wait(); });
  EXPECT_FALSE(ChildProcess::fork([] { return 0; }, {}, 60s)) << "a thread of ours is running";
  release.set_value();
  busy.join();
}

TEST(ChildProcess, SetsTheGivenEnvironmentOverOurs) {
  setenv("XSHADE_SUBPROCESS_TEST", "ours", 1);
  ChildProcess child = shell("echo $XSHADE_SUBPROCESS_TEST $XSHADE_SUBPROCESS_OTHER",
                             {"XSHADE_SUBPROCESS_TEST=theirs", "XSHADE_SUBPROCESS_OTHER=2"});
  finish(child);
  EXPECT_EQ(child.output(), "theirs 2\n");
}

TEST(ChildProcess, NoChildOutlivesItsObject) {
  pid_t pid = -1;
  {
    ChildProcess child = shell("echo $$ >&3; exec sleep 30");
    while (child.last_status().empty() && !child.poll()) wait_for_any({&child}, 100ms);
    pid = std::stoi(child.last_status());
    ChildProcess moved = std::move(child);  // the moved-to object owns it now
    EXPECT_FALSE(moved.finished());
    EXPECT_EQ(kill(pid, 0), 0);
  }
  EXPECT_EQ(kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH);
}

TEST(ChildProcess, KeepsTheStartAndTheEndOfAFloodOfOutput) {
  ChildProcess child = shell("echo first; head -c 3000000 /dev/zero | tr '\\0' a; echo; echo last");
  finish(child);
  EXPECT_LE(child.output().size(), ChildProcess::kOutputKept + 100);
  EXPECT_TRUE(child.output().starts_with("first\n"));
  EXPECT_TRUE(child.output().ends_with("last\n"));
  EXPECT_NE(child.output().find("bytes of output left out"), std::string::npos);
}

TEST(ChildProcess, AProgramThatCannotStartIsAnError) {
  auto child = ChildProcess::start({"/nonexistent/program"}, {}, 1s);
  EXPECT_FALSE(child);
}

}  // namespace
}  // namespace xshade
