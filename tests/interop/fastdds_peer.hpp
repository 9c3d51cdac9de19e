#pragma once
// A Fast DDS participant for the interop programs (Debian's Fast DDS 2.9): loopback only, no
// shared memory (it only works Fast <-> Fast), Cyclone found by unicast (on lo Cyclone does not
// multicast), and endpoints with the QoS each program plays.
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <memory>
#include <string>

namespace colag::interop {

struct FastDdsPeer {
  eprosima::fastdds::dds::DomainParticipant* participant = nullptr;
  eprosima::fastdds::dds::Publisher* pub = nullptr;
  eprosima::fastdds::dds::Subscriber* sub = nullptr;

  bool init(unsigned domain, const char* name) {
    using namespace eprosima::fastdds::dds;
    DomainParticipantQos pq;
    pq.name(name);
    pq.transport().use_builtin_transports = false;
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    udp->interfaceWhiteList.emplace_back("127.0.0.1");
    pq.transport().user_transports.push_back(udp);
    eprosima::fastrtps::rtps::Locator_t peer;
    eprosima::fastrtps::rtps::IPLocator::setIPv4(peer, 127, 0, 0, 1);
    pq.wire_protocol().builtin.initialPeersList.push_back(peer);
    pq.wire_protocol().builtin.discovery_config.leaseDuration_announcementperiod = {0, 200000000};
    participant = DomainParticipantFactory::get_instance()->create_participant(domain, pq);
    if (participant == nullptr) return false;
    pub = participant->create_publisher(PUBLISHER_QOS_DEFAULT);
    sub = participant->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
    return pub != nullptr && sub != nullptr;
  }
  eprosima::fastdds::dds::Topic* topic(const std::string& name,
                                       eprosima::fastdds::dds::TopicDataType* type) {
    using namespace eprosima::fastdds::dds;
    TypeSupport ts(type);
    ts.register_type(participant);
    return participant->create_topic(name, ts.get_type_name(), TOPIC_QOS_DEFAULT);
  }
  eprosima::fastdds::dds::DataWriter* writer(const std::string& name,
                                             eprosima::fastdds::dds::TopicDataType* type,
                                             bool reliable, bool transient_local, int depth) {
    using namespace eprosima::fastdds::dds;
    Topic* t = topic(name, type);
    if (t == nullptr) return nullptr;
    DataWriterQos q = DATAWRITER_QOS_DEFAULT;
    q.reliability().kind = reliable ? RELIABLE_RELIABILITY_QOS : BEST_EFFORT_RELIABILITY_QOS;
    q.durability().kind =
        transient_local ? TRANSIENT_LOCAL_DURABILITY_QOS : VOLATILE_DURABILITY_QOS;
    q.history().kind = KEEP_LAST_HISTORY_QOS;
    q.history().depth = depth;
    q.data_sharing().off();
    return pub->create_datawriter(t, q);
  }
  eprosima::fastdds::dds::DataReader* reader(const std::string& name,
                                             eprosima::fastdds::dds::TopicDataType* type,
                                             bool reliable, int depth) {
    using namespace eprosima::fastdds::dds;
    Topic* t = topic(name, type);
    if (t == nullptr) return nullptr;
    DataReaderQos q = DATAREADER_QOS_DEFAULT;
    q.reliability().kind = reliable ? RELIABLE_RELIABILITY_QOS : BEST_EFFORT_RELIABILITY_QOS;
    q.durability().kind = VOLATILE_DURABILITY_QOS;
    q.history().kind = KEEP_LAST_HISTORY_QOS;
    q.history().depth = depth;
    q.data_sharing().off();
    return sub->create_datareader(t, q);
  }
};

}  // namespace colag::interop
