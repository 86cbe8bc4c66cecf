// The reasoner from C++ through its C API (crates/capi/include/proclaim.h): load the microwave
// theory, set its inputs as sensors would, and ask whether it cooks under every algorithm.
// crates/capi/tests/cpp.rs builds and runs it and compares its output with the Rust session's:
//   g++ -std=c++17 -I crates/capi/include examples/cpp/microwave.cpp
//       target/debug/libproclaim_capi.a -lpthread -ldl -lm -o microwave
//   ./microwave theories/microwave.dl

#include "proclaim.h"

#include <iostream>
#include <memory>
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

// The status's name and the detail: which atom, which argument.
inline void check(ProclaimStatus status, const std::string& what) {
  if (status != PROCLAIM_STATUS_OK) {
    throw Error(what + ": " + proclaim_status_name(status) + ": " + proclaim_last_error_message());
  }
}

inline Owned<ProclaimTheory> load_file(const std::string& path) {
  ProclaimError* raw_error = nullptr;
  Owned<ProclaimTheory> theory(proclaim_theory_load_file(path.c_str(), &raw_error));
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
  try {
    auto theory = proclaim::load_file(path);
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
