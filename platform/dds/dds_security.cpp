#include "colag/platform/dds/dds_security.hpp"

#include <cstdio>
#include <string>

namespace colag::platform::dds {

Status add_security(const DdsSecurityConfig& sec, dds_qos_t* qos) {
  struct File {
    const std::string& path;
    const char* property;
    const char* missing;
  };
  const File files[] = {
      {sec.identity_ca, "dds.sec.auth.identity_ca", "DDS security: identity_ca unreadable"},
      {sec.certificate, "dds.sec.auth.identity_certificate",
       "DDS security: certificate unreadable"},
      {sec.private_key, "dds.sec.auth.private_key", "DDS security: private_key unreadable"},
      {sec.permissions_ca, "dds.sec.access.permissions_ca",
       "DDS security: permissions_ca unreadable"},
      {sec.governance, "dds.sec.access.governance", "DDS security: governance unreadable"},
      {sec.permissions, "dds.sec.access.permissions", "DDS security: permissions unreadable"},
  };
  for (const File& f : files) {
    if (std::FILE* fp = std::fopen(f.path.c_str(), "rb")) {
      std::fclose(fp);
    } else {
      return {Errc::kInvalidArgument, f.missing};
    }
    dds_qset_prop(qos, f.property, ("file:" + f.path).c_str());
  }
  const std::string dir = sec.plugin_dir.empty() ? COLAG_DDS_SECURITY_PLUGIN_DIR : sec.plugin_dir;
  const struct {
    const char* kind;
    const char* library;
    const char* init;
    const char* fini;
  } plugins[] = {
      {"auth", "libdds_security_auth.so", "init_authentication", "finalize_authentication"},
      {"access", "libdds_security_ac.so", "init_access_control", "finalize_access_control"},
      {"crypto", "libdds_security_crypto.so", "init_crypto", "finalize_crypto"},
  };
  for (const auto& p : plugins) {
    const std::string prefix = std::string("dds.sec.") + p.kind + ".library.";
    dds_qset_prop(qos, (prefix + "path").c_str(), (dir + "/" + p.library).c_str());
    dds_qset_prop(qos, (prefix + "init").c_str(), p.init);
    dds_qset_prop(qos, (prefix + "finalize").c_str(), p.fini);
  }
  return Status::ok();
}

}  // namespace colag::platform::dds
