#include <gtest/gtest.h>

#include <set>
#include <string>

#include "colag/msg/topics.hpp"

using namespace colag;
using namespace colag::msg;

TEST(Topics, TableIsCompleteAndConsistent) {
  std::set<std::string> names;
  for (const TopicInfo& t : kTopicTable) {
    EXPECT_TRUE(names.insert(t.name).second) << "duplicate topic name " << t.name;
    EXPECT_GT(t.history_depth, 0);
    EXPECT_LE(t.size_bytes, kMaxMessageBytes);
    const std::size_t size = visit_message_type(t.topic, []<class M>() { return sizeof(M); });
    EXPECT_EQ(size, t.size_bytes) << t.name;
  }
  EXPECT_EQ(names.size(), kTopicCount);
  // Requests and plans must never be silently lost.
  EXPECT_EQ(topic_info(Topic::kCollisionInfo).reliability, Reliability::kReliable);
  EXPECT_EQ(topic_info(Topic::kMapPatch).reliability, Reliability::kReliable);
}

TEST(Topics, KeysAreTheRobotTheMessageIsAbout) {
  RelativePose rp;
  rp.uav_id = 0;
  rp.ugv_id = 7;
  EXPECT_EQ(message_key(Topic::kRelativePose, &rp), 7);
  MapPatch mp;
  mp.ugv_id = 3;
  EXPECT_EQ(message_key(Topic::kMapPatch, &mp), 3);
  CollisionInfo ci;
  ci.ugv_id = 11;
  EXPECT_EQ(message_key(Topic::kCollisionInfo, &ci), 11);
  UgvStatus st;
  st.ugv_id = 15;
  EXPECT_EQ(message_key(Topic::kUgvStatus, &st), 15);
  UavOdometry od;
  od.uav_id = 2;
  EXPECT_EQ(message_key(Topic::kUavOdometry, &od), 2);
  SupportPlan sp;
  sp.uav_id = 1;
  EXPECT_EQ(message_key(Topic::kSupportPlan, &sp), 1);
}

TEST(Topics, MessagesStartWithTheirStamp) {
  EXPECT_EQ(offsetof(UavOdometry, stamp), 0u);
  EXPECT_EQ(offsetof(RelativePose, stamp), 0u);
  EXPECT_EQ(offsetof(MapPatch, stamp), 0u);
  EXPECT_EQ(offsetof(CollisionInfo, stamp), 0u);
  EXPECT_EQ(offsetof(UgvStatus, stamp), 0u);
  EXPECT_EQ(offsetof(SupportPlan, stamp), 0u);
}
