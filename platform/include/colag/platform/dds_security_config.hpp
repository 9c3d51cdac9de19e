#pragma once
// DDS Security for a robot's participant (Cyclone DDS's authentication, access-control and
// cryptography plugins): the six files scripts/security/make-pki creates for each robot. All
// empty: security off. Read once at start-up (strings are fine here).
#include <string>

namespace colag::platform {

struct DdsSecurityConfig {
  std::string identity_ca;     // CA that signed every robot's identity (PEM)
  std::string certificate;     // this robot's identity certificate (PEM)
  std::string private_key;     // its private key (PEM)
  std::string permissions_ca;  // CA that signed governance and permissions (PEM)
  std::string governance;      // signed governance document (S/MIME, .p7s)
  std::string permissions;     // this robot's signed permissions document (.p7s)
  std::string plugin_dir;      // where libdds_security_*.so are; empty: Debian's location

  bool enabled() const {
    return !identity_ca.empty() || !certificate.empty() || !private_key.empty() ||
           !permissions_ca.empty() || !governance.empty() || !permissions.empty();
  }
};

}  // namespace colag::platform
