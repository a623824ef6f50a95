// mbk bag's outputs in a folder others can write to: the temporary file is created exclusively
// under an unpredictable name (a link planted at a name it could have is never written through),
// checked to be still the file created before it is renamed, and a link found at a side file's
// name is replaced, never followed (offline/output_file.h). A run ended by SIGINT, SIGTERM or
// SIGHUP removes its temporary files; one ended by SIGKILL leaves them to the next run on the
// same output, which removes them.
#include "mb_kinematics/offline/output_file.h"

#include <glob.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "mb_kinematics/io/load_model.h"
#include "mb_kinematics/offline/bag_command.h"

namespace {

const std::string kModel = MBK_SOURCE_DIR "/config/human_body.yaml";

std::string temp(const std::string& name) { return ::testing::TempDir() + name; }

std::string read_file(const std::string& path) {
  std::ifstream f(path);
  std::stringstream text;
  text << f.rdbuf();
  return text.str();
}

// A trajectory CSV of kModel's coordinates: `rows` samples at 100 Hz from t = 1 s.
std::string write_trajectory(const std::string& name, int rows) {
  const mbk::Model model = mbk::load_model_file(kModel);
  std::ofstream f(temp(name));
  f << "time";
  for (const std::string& c : model.coordinate_names) f << "," << c;
  f << "\n";
  for (int i = 0; i < rows; ++i) {
    const double t = 1.0 + i / 100.0;
    f << t;
    for (int c = 0; c < model.nq; ++c) f << "," << 0.3 * std::sin(t + c);
    f << "\n";
  }
  return temp(name);
}

mbk_offline::BagOptions options(const std::string& in) {
  mbk_offline::BagOptions o;
  o.input = in;
  o.model = kModel;
  return o;
}

bool is_link(const std::string& path) {
  struct stat st;
  return lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode);
}

// The name a run's temporary file had before (`OUT.mbk-tmp-PID`) is predictable: a link planted
// there by another user must not make the run write into the link's target.
TEST(OutputFileTest, ALinkAtAPredictableTemporaryNameIsNotWrittenThrough) {
  const std::string in = write_trajectory("planted_in.csv", 50);
  const std::string victim = temp("planted_victim.txt");
  std::ofstream(victim) << "someone else's file";
  mbk_offline::BagOptions o = options(in);
  o.out_bag = temp("planted_out.bag");
  o.out_csv = temp("planted_out.csv");
  for (const std::string& out : {o.out_bag, o.out_csv}) {
    std::remove(out.c_str());
    const std::string planted = out + ".mbk-tmp-" + std::to_string(getpid());
    std::remove(planted.c_str());
    ASSERT_EQ(symlink(victim.c_str(), planted.c_str()), 0);
  }
  mbk_offline::run_bag(o);
  EXPECT_EQ(read_file(victim), "someone else's file");
  EXPECT_GT(read_file(o.out_csv).size(), 1000u);
  for (const std::string& out : {o.out_bag, o.out_csv})
    std::remove((out + ".mbk-tmp-" + std::to_string(getpid())).c_str());
}

// Each output's temporary file has a name of its own (two at once for one path differ), made
// by this process, with the permissions a new file gets (not mkstemp's 0600).
TEST(OutputFileTest, TemporaryNamesAreUnpredictableAndExclusive) {
  const std::string out = temp("exclusive.csv");
  mbk_offline::OutputFile a(out), b(out);
  EXPECT_NE(a.writing(), b.writing());
  const std::string prefix = out + ".mbk-tmp-" + std::to_string(getpid()) + "-";
  for (const mbk_offline::OutputFile* f : {&a, &b}) {
    EXPECT_EQ(f->writing().rfind(prefix, 0), 0u) << f->writing();
    EXPECT_EQ(f->writing().size(), prefix.size() + 6) << f->writing();
    struct stat st;
    ASSERT_EQ(lstat(f->writing().c_str(), &st), 0) << f->writing();
    EXPECT_TRUE(S_ISREG(st.st_mode));
    const mode_t mask = umask(0);
    umask(mask);
    EXPECT_EQ(st.st_mode & 0777, 0666 & ~mask);
  }
}

// A temporary file replaced while it is written (here by a link to another file) is not renamed
// over the output: an error, the output and the link's target left as they were.
TEST(OutputFileTest, ATemporaryFileReplacedWhileWrittenIsNotRenamed) {
  const std::string out = temp("swapped.csv"), victim = temp("swapped_victim.txt");
  std::ofstream(out) << "the previous output";
  std::ofstream(victim) << "someone else's file";
  mbk_offline::OutputFile file(out);
  ASSERT_NE(file.writing(), out);
  ASSERT_EQ(std::remove(file.writing().c_str()), 0);
  ASSERT_EQ(symlink(victim.c_str(), file.writing().c_str()), 0);
  try {
    file.commit();
    ADD_FAILURE() << "a replaced temporary file was renamed";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("replaced while it was written"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_file(out), "the previous output");
  EXPECT_EQ(read_file(victim), "someone else's file");
}

// The error bars' side files (OUT.errors.csv, OUT.sample_errors.csv) are not named by the user:
// a link found at their names (to /dev/null here; to a device or a pipe of another user) is
// replaced by the new file, not written through.
TEST(OutputFileTest, ALinkAtASideFileIsReplacedNotFollowed) {
  const std::string in = write_trajectory("side_link_in.csv", 100);
  mbk_offline::BagOptions o = options(in);
  o.out_csv = temp("side_link.csv");
  for (const char* name : {"side_link.errors.csv", "side_link.sample_errors.csv"}) {
    std::remove(temp(name).c_str());
    ASSERT_EQ(symlink("/dev/null", temp(name).c_str()), 0);
  }
  mbk_offline::run_bag(o);
  for (const char* name : {"side_link.errors.csv", "side_link.sample_errors.csv"}) {
    EXPECT_FALSE(is_link(temp(name))) << name;
    EXPECT_GT(read_file(temp(name)).size(), 100u) << name;
  }
}

// The paths matching a shell pattern.
std::vector<std::string> matching(const std::string& pattern) {
  glob_t found;
  std::vector<std::string> paths;
  if (glob(pattern.c_str(), 0, nullptr, &found) == 0)
    paths.assign(found.gl_pathv, found.gl_pathv + found.gl_pathc);
  globfree(&found);
  return paths;
}

// `mbk bag` on a long recording (10,000 samples: its outputs take seconds to write) into OUT.bag
// and OUT.csv, started in a child process with SIGINT, SIGTERM and SIGHUP at their default
// actions and unblocked, whatever this process inherited (`ignored`, if not 0, ignored instead),
// its error output in OUT.err. Returns it stopped (SIGSTOP) 200 ms after its first temporary file
// appeared, its temporary files still there: a signal sent now reaches it while it writes its
// outputs, however fast the machine (continue it with SIGCONT).
pid_t start_long_run(const std::string& out, int ignored = 0) {
  static const std::string in = write_trajectory("long_run.csv", 10000);
  const pid_t pid = fork();
  if (pid == 0) {
    freopen((out + ".err").c_str(), "w", stderr);
    sigset_t signals;
    sigemptyset(&signals);
    for (const int s : {SIGINT, SIGTERM, SIGHUP}) {
      std::signal(s, s == ignored ? SIG_IGN : SIG_DFL);
      sigaddset(&signals, s);
    }
    sigprocmask(SIG_UNBLOCK, &signals, nullptr);
    execl(MBK_MBK_PATH, "mbk", "bag", in.c_str(), "--model", kModel.c_str(), "--out",
          (out + ".bag").c_str(), "--csv", (out + ".csv").c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 6000 && matching(out + ".*.mbk-tmp-*").empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_FALSE(matching(out + ".*.mbk-tmp-*").empty()) << "no temporary file after 60 s";
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  int status = 0;
  EXPECT_EQ(kill(pid, SIGSTOP), 0);
  EXPECT_EQ(waitpid(pid, &status, WUNTRACED), pid);
  EXPECT_TRUE(WIFSTOPPED(status)) << "the run ended before it was stopped: status " << status;
  EXPECT_FALSE(matching(out + ".*.mbk-tmp-*").empty()) << "stopped after writing its outputs";
  return pid;
}

// Sends `signal` to a run start_long_run stopped, and continues it.
void signal_stopped_run(pid_t pid, int signal) {
  ASSERT_EQ(kill(pid, signal), 0);
  ASSERT_EQ(kill(pid, SIGCONT), 0);
}

// Ended by SIGINT, SIGTERM or SIGHUP while writing, a run leaves no temporary file, ends by the
// signal (as it would have without the cleanup), and the previous outputs stay as they were.
TEST(OutputFileTest, SignalsRemoveTheTemporaryFiles) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP}) {
    const std::string out = temp("signalled_" + std::to_string(signal));
    std::ofstream(out + ".bag") << "the previous bag";
    std::ofstream(out + ".csv") << "the previous csv";
    const pid_t pid = start_long_run(out);
    signal_stopped_run(pid, signal);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
        << "signal " << signal << ": status " << status
        << "; its errors: " << read_file(out + ".err");
    EXPECT_EQ(matching(out + ".*.mbk-tmp-*"), std::vector<std::string>{}) << signal;
    EXPECT_EQ(read_file(out + ".bag"), "the previous bag");
    EXPECT_EQ(read_file(out + ".csv"), "the previous csv");
  }
}

// A run started ignoring SIGTERM (nohup does so with SIGHUP) keeps ignoring it: sent one while it
// writes, it goes on and renames its outputs into place. (Handled, the signal removed the
// temporary files of a run that went on, which then failed naming them "replaced".)
TEST(OutputFileTest, ASignalIgnoredFromTheStartStaysIgnored) {
  const std::string out = temp("ignoring");
  std::ofstream(out + ".csv") << "the previous csv";
  const pid_t pid = start_long_run(out, SIGTERM);
  signal_stopped_run(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << "status " << status << "; its errors: " << read_file(out + ".err");
  EXPECT_EQ(matching(out + ".*.mbk-tmp-*"), std::vector<std::string>{});
  EXPECT_EQ(read_file(out + ".csv").rfind("stamp,body,", 0), 0u)
      << "the run's CSV, not the previous one";
}

// What a run killed by SIGKILL leaves (its process gone) is removed by the next run on the same
// output; a temporary file of a process still running (here this test's) is left alone.
TEST(OutputFileTest, TheNextRunRemovesAKilledRunsTemporaryFiles) {
  const std::string out = temp("killed");
  const pid_t pid = start_long_run(out);
  ASSERT_EQ(kill(pid, SIGKILL), 0);  // a stopped process too
  ASSERT_EQ(waitpid(pid, nullptr, 0), pid);
  ASSERT_FALSE(matching(out + ".*.mbk-tmp-*").empty());
  const std::string running = out + ".csv.mbk-tmp-" + std::to_string(getpid()) + "-abcdef";
  std::ofstream(running) << "a run still writing";
  mbk_offline::BagOptions o = options(write_trajectory("after_kill.csv", 20));
  o.out_bag = out + ".bag";
  o.out_csv = out + ".csv";
  mbk_offline::run_bag(o);
  EXPECT_EQ(matching(out + ".*.mbk-tmp-*"), std::vector<std::string>{running});
  std::remove(running.c_str());
}

}  // namespace
