// The reader of rosbag2's sqlite3 storage on a file written here with rosbag2's schema: topics
// with their types and spans, messages of the topics asked for in time order (whatever the order
// of the rows), and a file that is not a bag is an error naming it.
#include "io/sqlite_bag.h"

#include <gtest/gtest.h>

#include <fstream>

#include "io/input_error.h"
#include "tests/import_test_util.h"
#include "tests/ros2_bag_writer.h"

namespace slipgraph {
namespace {

TEST(SqliteBag, TopicsAndMessagesInTimeOrder) {
  std::vector<testing::StoredMessage> written;
  for (int i = 9; i >= 0; --i) {  // rows written newest first
    RosOdometry odom;
    odom.stamp_s = 5.0 + 0.1 * i;
    odom.linear = {0.1 * i, 0.0, 0.0};
    written.push_back(testing::Store("/odom", odom.stamp_s, odom));
    RosNavSatFix fix;
    fix.stamp_s = 5.0 + 0.1 * i;
    written.push_back(testing::Store("/fix", fix.stamp_s, fix));
  }
  const std::string path = ::testing::TempDir() + "/order.db3";
  testing::WriteSqliteBag(path, written);
  ASSERT_TRUE(IsSqliteFile(path));
  const std::vector<BagTopic> topics = ListSqliteBag(path);
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].name, "/fix");
  EXPECT_EQ(topics[1].name, "/odom");
  EXPECT_EQ(topics[1].type, "nav_msgs/msg/Odometry");
  EXPECT_EQ(topics[1].count, 10);
  EXPECT_EQ(topics[1].first_ns, 5000000000);
  EXPECT_EQ(topics[1].last_ns, 5900000000);
  std::vector<int64_t> times;
  ReadSqliteBag(path, {"/odom"}, [&](const BagTopic& topic, int64_t t, const uint8_t*, size_t n) {
    EXPECT_EQ(topic.name, "/odom");
    EXPECT_GT(n, 4u);
    times.push_back(t);
  });
  ASSERT_EQ(times.size(), 10u);
  EXPECT_TRUE(std::is_sorted(times.begin(), times.end()));
}

TEST(SqliteBag, AFileThatIsNotABagIsAnErrorNamingIt) {
  const std::string path = ::testing::TempDir() + "/not_a_bag.db3";
  std::ofstream(path) << "SQLite format 3 but nothing after it";
  const std::string e = testing::ErrorOf([&] { ListSqliteBag(path); });
  EXPECT_NE(e.find("not_a_bag.db3"), std::string::npos) << e;
  EXPECT_NE(e.find("not a readable rosbag2 sqlite3 file"), std::string::npos) << e;
}

}  // namespace
}  // namespace slipgraph
