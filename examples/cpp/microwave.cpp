// The reasoner from C++ through its C API (crates/capi/include/proclaim.h): load the microwave
// theory, set its inputs as sensors would, and ask whether it cooks under every algorithm.
// crates/capi/tests/cpp.rs builds and runs it and compares its output with the Rust session's:
//   g++ -std=c++17 -I crates/capi/include examples/cpp/microwave.cpp
//       target/debug/libproclaim_capi.a -lpthread -ldl -lm -o microwave
//   ./microwave theories/microwave.dl

#include "proclaim.h"

#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

namespace proclaim {

// Every handle is freed by its own function; unique_ptr calls it however the scope is left.
struct Free {
  void operator()(ProclaimTheory* theory) const { proclaim_theory_free(theory); }
  void operator()(ProclaimSession* session) const { proclaim_session_free(session); }
  void operator()(ProclaimError* error) const { proclaim_error_free(error); }
};
template <class Handle>
using Owned = std::unique_ptr<Handle, Free>;

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void check(ProclaimStatus status, const std::string& what) {
  if (status != PROCLAIM_STATUS_OK) throw Error(what + ": " + proclaim_status_name(status));
}

inline Owned<ProclaimTheory> load(const std::string& name, const std::string& text) {
  ProclaimError* raw_error = nullptr;
  Owned<ProclaimTheory> theory(
      proclaim_theory_load_named(name.c_str(), text.data(), text.size(), &raw_error));
  Owned<ProclaimError> error(raw_error);
  if (!theory) throw Error(error->message);
  return theory;
}

class Session {
 public:
  explicit Session(const Owned<ProclaimTheory>& theory) : session_(proclaim_session_new(theory.get())) {}
  void set(const char* atom, ProclaimValue value) {
    check(proclaim_session_set(session_.get(), atom, value), atom);
  }
  bool prove(const char* literal, ProclaimAlgorithm algorithm) {
    bool answer = false;
    check(proclaim_session_prove(session_.get(), literal, algorithm, &answer), literal);
    return answer;
  }

 private:
  Owned<ProclaimSession> session_;
};

}  // namespace proclaim

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "theories/microwave.dl";
  std::ifstream file(path);
  if (!file) {
    std::cerr << "cannot read " << path << "\n";
    return 1;
  }
  std::ostringstream text;
  text << file.rdbuf();
  try {
    auto theory = proclaim::load(path, text.str());
    proclaim::Session session(theory);
    const struct {
      const char* name;
      ProclaimAlgorithm algorithm;
    } algorithms[] = {{"mu", PROCLAIM_ALGORITHM_MU},
                      {"pi", PROCLAIM_ALGORITHM_PI},
                      {"beta", PROCLAIM_ALGORITHM_BETA},
                      {"alpha", PROCLAIM_ALGORITHM_ALPHA},
                      {"delta", PROCLAIM_ALGORITHM_DELTA}};
    for (bool door_open : {false, true}) {
      for (bool time_left : {false, true}) {
        session.set("doorOpen", door_open ? PROCLAIM_VALUE_TRUE : PROCLAIM_VALUE_FALSE);
        session.set("timeLeft", time_left ? PROCLAIM_VALUE_TRUE : PROCLAIM_VALUE_FALSE);
        std::cout << std::boolalpha << "doorOpen=" << door_open << " timeLeft=" << time_left
                  << " cook:";
        for (const auto& each : algorithms) {
          std::cout << " " << each.name << "=" << session.prove("cook", each.algorithm);
        }
        std::cout << "\n";
      }
    }
  } catch (const proclaim::Error& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
  return 0;
}
