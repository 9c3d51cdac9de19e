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
  EXPECT_EQ(topic_info(topic_of<CollisionInfo>).reliability, Reliability::kReliable);
  EXPECT_EQ(topic_info(topic_of<MapPatch>).reliability, Reliability::kReliable);
}

TEST(Topics, KeysAreTheRobotTheMessageIsAbout) {
  RelativePose rp;
  rp.uav_id = 0;
  rp.ugv_id = 7;
  EXPECT_EQ(message_key(topic_of<RelativePose>, &rp), 7);
  MapPatch mp;
  mp.ugv_id = 3;
  EXPECT_EQ(message_key(topic_of<MapPatch>, &mp), 3);
  CollisionInfo ci;
  ci.ugv_id = 11;
  EXPECT_EQ(message_key(topic_of<CollisionInfo>, &ci), 11);
  UgvStatus st;
  st.ugv_id = 15;
  EXPECT_EQ(message_key(topic_of<UgvStatus>, &st), 15);
  UavOdometry od;
  od.uav_id = 2;
  EXPECT_EQ(message_key(topic_of<UavOdometry>, &od), 2);
  SupportPlan sp;
  sp.uav_id = 1;
  EXPECT_EQ(message_key(topic_of<SupportPlan>, &sp), 1);
}

TEST(Topics, MessagesStartWithTheirStamp) {
  for_each_message_type([]<class Msg>() {
    EXPECT_EQ(Fields<Msg>::kNames[0], "stamp") << Fields<Msg>::kType;
    EXPECT_TRUE((std::is_same_v<
                 std::remove_cvref_t<decltype(std::get<0>(Fields<Msg>::tie(std::declval<Msg&>())))>,
                 TimePoint>))
        << Fields<Msg>::kType;
  });
}

TEST(Topics, TopicOfIsTheIndexInTheTable) {
  for_each_message_type([]<class Msg>() {
    EXPECT_EQ(topic_info(topic_of<Msg>).size_bytes, sizeof(Msg));
    EXPECT_STREQ(topic_info(topic_of<Msg>).name, kTopicSpec<Msg>.name);
  });
}
