// Tests of private_directory.hpp: a directory only the controller's user can write, and files
// created in it exclusively, never through a link, mode 0600.
#include "hapticctrl/program/private_directory.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <sstream>
#include <string>

#include "support/temp_directory.hpp"

namespace hapticctrl::program {
namespace {

using test::TempDirectory;

std::string contents(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string refusal(const std::string& path) {
  try {
    PrivateDirectory refused(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(PrivateDirectory, CreatesFilesOnlyItsOwnerCanReadWhateverTheUmask) {
  TempDirectory temp("private");
  const PrivateDirectory dir(temp.path());
  const mode_t old_umask = umask(0);
  const bool created = dir.create_file("box.csv", "a,b\n1,2\n");
  umask(old_umask);
  ASSERT_TRUE(created);
  struct stat st {};
  ASSERT_EQ(stat((temp / "box.csv").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600U);
  EXPECT_EQ(contents(temp / "box.csv"), "a,b\n1,2\n");
  EXPECT_FALSE(dir.create_file("box.csv", "again")) << "never replaced";
  EXPECT_EQ(contents(temp / "box.csv"), "a,b\n1,2\n");
  EXPECT_THROW((void)dir.create_file("../escape", "x"), std::invalid_argument);
}

TEST(PrivateDirectory, RefusesADirectoryItsGroupOrOthersMayWrite) {
  TempDirectory temp("private");
  ASSERT_EQ(chmod(temp.path().c_str(), 0770), 0);
  EXPECT_NE(refusal(temp.path()).find("may be written by its group or by others (mode 770)"),
            std::string::npos)
      << refusal(temp.path());
  ASSERT_EQ(chmod(temp.path().c_str(), 0750), 0);
  EXPECT_EQ(refusal(temp.path()), "") << "group may read and enter, not write";
  EXPECT_NE(refusal("/tmp").find("may be written"), std::string::npos) << "the old default";
}

TEST(PrivateDirectory, RefusesASymlinkAndWhatIsMissing) {
  TempDirectory temp("private");
  ASSERT_EQ(mkdir((temp / "real").c_str(), 0700), 0);
  ASSERT_EQ(symlink((temp / "real").c_str(), (temp / "link").c_str()), 0);
  EXPECT_NE(refusal(temp / "link").find("is not a directory"), std::string::npos)
      << refusal(temp / "link");
  EXPECT_NE(refusal(temp / "missing").find("cannot open the directory"), std::string::npos);
}

TEST(PrivateDirectory, NeverFollowsALinkPlantedAtTheName) {
  TempDirectory temp("private");
  ASSERT_EQ(mkdir((temp / "dir").c_str(), 0700), 0);
  { std::ofstream(temp / "victim") << "precious"; }
  ASSERT_EQ(symlink((temp / "victim").c_str(), (temp / "dir/box.csv").c_str()), 0);
  ASSERT_EQ(symlink((temp / "absent").c_str(), (temp / "dir/dangling.csv").c_str()), 0);
  const PrivateDirectory dir(temp / "dir");
  EXPECT_FALSE(dir.create_file("box.csv", "overwritten"));
  EXPECT_FALSE(dir.create_file("dangling.csv", "created through the link"));
  EXPECT_EQ(contents(temp / "victim"), "precious");
  EXPECT_NE(access((temp / "absent").c_str(), F_OK), 0) << "nothing created at the link's target";
}

TEST(PrivateDirectory, ListsMatchingRegularFilesOldestFirstAndRemovesThem) {
  TempDirectory temp("private");
  const PrivateDirectory dir(temp.path());
  for (const char* name : {"bb-new.csv", "bb-old.csv", "bb-mid.csv", "other.csv", "bb-x.txt"}) {
    ASSERT_TRUE(dir.create_file(name, "x"));
  }
  const auto age = [&](const char* name, time_t seconds) {
    const timespec times[2] = {{seconds, 0}, {seconds, 0}};  // NOLINT(*-avoid-c-arrays)
    ASSERT_EQ(utimensat(AT_FDCWD, (temp / name).c_str(), times, 0), 0);
  };
  age("bb-old.csv", 1000);
  age("bb-mid.csv", 2000);
  age("bb-new.csv", 3000);
  ASSERT_EQ(symlink((temp / "bb-old.csv").c_str(), (temp / "bb-link.csv").c_str()), 0);
  EXPECT_EQ(dir.files("bb-", ".csv"),
            (std::vector<std::string>{"bb-old.csv", "bb-mid.csv", "bb-new.csv"}))
      << "links are not listed";
  EXPECT_TRUE(dir.remove("bb-link.csv"));
  EXPECT_EQ(contents(temp / "bb-old.csv"), "x") << "the link went, not its target";
  EXPECT_TRUE(dir.remove("bb-old.csv"));
  EXPECT_FALSE(dir.remove("bb-old.csv"));
}

TEST(PrivateDirectory, ReadsOnlyRegularFilesNeverThroughALink) {
  TempDirectory temp("private");
  const PrivateDirectory dir(temp.path());
  ASSERT_TRUE(dir.create_file("note", "latched\n"));
  ASSERT_EQ(symlink((temp / "note").c_str(), (temp / "link").c_str()), 0);
  EXPECT_EQ(dir.read_file("note"), "latched\n");
  EXPECT_EQ(dir.read_file("link"), "") << "not through a link";
  EXPECT_EQ(dir.read_file("absent"), "");
  EXPECT_TRUE(dir.contains("note"));
  EXPECT_TRUE(dir.contains("link"));
  EXPECT_FALSE(dir.contains("absent"));
}

TEST(PrivateDirectory, AnotherUserCannotPlantALinkInIt) {
  if (geteuid() != 0) {
    GTEST_SKIP() << "needs root to act as another user (CI runs as root)";
  }
  TempDirectory temp("private");
  ASSERT_EQ(chmod(temp.path().c_str(), 0755), 0);  // others may look, as in /var/lib
  const PrivateDirectory dir(temp.path());
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    constexpr uid_t kNobody = 65534;
    if (setgid(kNobody) != 0 || setuid(kNobody) != 0) {
      _exit(2);
    }
    const int planted = symlink("/etc/passwd", (temp / "hapticctrl-blackbox-x.1.csv").c_str());
    _exit(planted == 0 ? 1 : (errno == EACCES ? 0 : 3));
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "1: the link was planted; 2: could not become nobody";
}

}  // namespace
}  // namespace hapticctrl::program
