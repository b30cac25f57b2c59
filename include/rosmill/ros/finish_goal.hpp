// How every rosmill action ends a goal: PREEMPTED when the client cancelled it (the result still carries what was
// done), SUCCEEDED when it reached its aim, ABORTED otherwise; the result's message is the state's text.
#pragma once
#include <string>

namespace rosmill::edge {

template <typename Server, typename Result>
void finish_goal(Server& server, const Result& result, bool cancelled, bool succeeded) {
  if (cancelled)
    server.setPreempted(result, result.message);
  else if (succeeded)
    server.setSucceeded(result, result.message);
  else
    server.setAborted(result, result.message);
}

}  // namespace rosmill::edge
