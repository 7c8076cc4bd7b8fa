// The solver cache's folder (api/cache_folder.cpp): where it is, the owner
// and mode checks and their messages, private creation, and opening without
// following links.
#include "api/cache_folder.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <optional>
#include <string>

#include "tests/support/process.h"

namespace mbfe::test {
namespace {

// Sets (or with nullopt unsets) an environment variable for the test's
// lifetime, restoring it afterwards.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, std::optional<std::string> value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value) ::setenv(name, value->c_str(), 1);
    else ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_) ::setenv(name_, old_->c_str(), 1);
    else ::unsetenv(name_);
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

TEST(CacheFolder, FollowsMbfeThenXdgThenHome) {
  {
    ScopedEnv mbfe("MBFE_CACHE_DIR", "/a/cache"), xdg("XDG_CACHE_HOME", "/x"), home("HOME", "/h");
    EXPECT_EQ(solver_cache_dir(), "/a/cache");
  }
  {
    ScopedEnv mbfe("MBFE_CACHE_DIR", std::nullopt), xdg("XDG_CACHE_HOME", "/x"), home("HOME", "/h");
    EXPECT_EQ(solver_cache_dir(), "/x/mbfe");
  }
  {
    ScopedEnv mbfe("MBFE_CACHE_DIR", std::nullopt), xdg("XDG_CACHE_HOME", std::nullopt), home("HOME", "/h");
    EXPECT_EQ(solver_cache_dir(), "/h/.cache/mbfe");
  }
  {  // a relative XDG_CACHE_HOME is invalid (XDG base directory specification): ignored
    ScopedEnv mbfe("MBFE_CACHE_DIR", std::nullopt), xdg("XDG_CACHE_HOME", "rel"), home("HOME", "/h");
    EXPECT_EQ(solver_cache_dir(), "/h/.cache/mbfe");
  }
}

TEST(CacheFolder, NoSettingIsRefusedWithWhatToDo) {
  ScopedEnv mbfe("MBFE_CACHE_DIR", std::nullopt), xdg("XDG_CACHE_HOME", "relative"), home("HOME", "");
  try {
    solver_cache_dir();
    FAIL() << "a cache folder was made up";
  } catch (const CacheRefused& e) {
    EXPECT_NE(std::string(e.what()).find("set MBFE_CACHE_DIR"), std::string::npos) << e.what();
  }
}

struct stat stat_of(uid_t uid, mode_t mode) {
  struct stat st {};
  st.st_uid = uid;
  st.st_mode = mode;
  return st;
}

// The message of require_private, or "" when it accepts.
std::string refusal(const struct stat& st) {
  try {
    require_private(st, "/c/x", "solver cache entry");
    return "";
  } catch (const CacheRefused& e) {
    return e.what();
  }
}

TEST(CacheFolder, RequirePrivateAcceptsOnlyTheUsersOwnAndUnwritableByOthers) {
  const uid_t me = ::geteuid();
  EXPECT_EQ(refusal(stat_of(me, S_IFDIR | 0700)), "");
  EXPECT_EQ(refusal(stat_of(me, S_IFDIR | 0755)), "");  // readable by others is not a risk
  EXPECT_EQ(refusal(stat_of(me, S_IFREG | 0644)), "");
  EXPECT_EQ(refusal(stat_of(me, S_IFLNK | 0777)), "");  // a link's mode means nothing

  const std::string group = refusal(stat_of(me, S_IFDIR | 0775));
  EXPECT_EQ(group.rfind("/c/x: refusing the solver cache entry: it is writable by its group (", 0), 0u) << group;
  EXPECT_NE(group.find("mode 0775"), std::string::npos) << group;
  EXPECT_NE(group.find("chmod -R go-w '/c/x'"), std::string::npos) << group;
  EXPECT_NE(group.find("MBFE_CACHE_DIR"), std::string::npos) << group;
  EXPECT_NE(refusal(stat_of(me, S_IFDIR | 0703)).find("writable by others"), std::string::npos);
  EXPECT_NE(refusal(stat_of(me, S_IFDIR | 01777)).find("writable by its group and others"), std::string::npos);
  EXPECT_NE(refusal(stat_of(me, S_IFDIR | 01777)).find("mode 1777"), std::string::npos);

  const uid_t other = me == 0 ? 65534 : 0;
  const std::string foreign = refusal(stat_of(other, S_IFDIR | 0700));
  EXPECT_NE(foreign.find("it belongs to"), std::string::npos) << foreign;
  EXPECT_NE(foreign.find("uid " + std::to_string(other)), std::string::npos) << foreign;
  EXPECT_NE(foreign.find("mode 0700"), std::string::npos) << foreign;
  EXPECT_NE(refusal(stat_of(other, S_IFLNK | 0777)), "");  // another's link is refused too
}

TEST(CacheFolder, CreatesMissingFoldersPrivateWhateverTheUmask) {
  TempDir tmp;
  const mode_t old_umask = ::umask(0);
  const fs::path cache = tmp / "a" / "b" / "cache";
  {
    const UniqueFd fd = open_cache_folder(cache.string());
    EXPECT_TRUE(fd);
  }
  ::umask(old_umask);
  for (const fs::path& p : {tmp / "a", tmp / "a" / "b", cache}) {
    struct stat st {};
    ASSERT_EQ(::stat(p.c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, 0700u) << p;
  }
}

TEST(CacheFolder, OpensAnExistingFolderOfOthersNever) {
  TempDir tmp;
  const fs::path cache = tmp / "cache";
  fs::create_directory(cache);
  fs::permissions(cache, fs::perms::owner_all | fs::perms::group_all);
  EXPECT_THROW(open_cache_folder(cache.string()), CacheRefused);
  fs::permissions(cache, fs::perms::owner_all);
  EXPECT_NO_THROW(open_cache_folder(cache.string()));
}

TEST(CacheFolder, OpenBeneathFollowsNoLinkAndBlocksOnNoFifo) {
  TempDir tmp;
  const UniqueFd dir(::open(tmp.path().c_str(), O_RDONLY | O_DIRECTORY));
  ASSERT_TRUE(dir);
  spit(tmp / "file", "text");
  fs::create_symlink(tmp / "file", tmp / "link");
  ASSERT_EQ(::mkfifo((tmp / "fifo").c_str(), 0600), 0);

  const UniqueFd file(open_beneath(dir.get(), "file", O_RDONLY));
  ASSERT_TRUE(file);
  EXPECT_EQ(read_fd(file.get(), "file", 100), "text");
  EXPECT_THROW(read_fd(UniqueFd(open_beneath(dir.get(), "file", O_RDONLY)).get(), "file", 3), std::runtime_error);

  errno = 0;
  EXPECT_EQ(open_beneath(dir.get(), "link", O_RDONLY), -1);
  EXPECT_EQ(errno, ELOOP);

  const UniqueFd fifo(open_beneath(dir.get(), "fifo", O_RDONLY));  // returns at once
  ASSERT_TRUE(fifo);
  struct stat st {};
  ASSERT_EQ(::fstat(fifo.get(), &st), 0);
  EXPECT_FALSE(S_ISREG(st.st_mode));
}

}  // namespace
}  // namespace mbfe::test
