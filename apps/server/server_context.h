#pragma once
// Everything the request handlers share. Members are declared so that the
// render queue is destroyed first: its jobs finish before the sessions and
// volumes they use go away.
#include "server/data_directory.h"
#include "server/http_server.h"
#include "server/render_queue.h"
#include "server/session_memory.h"
#include "server/session_store.h"
#include "server/volume_cache.h"

namespace penumbra::server {

struct ServerContext {
  explicit ServerContext(ServerOptions opts)
      : options(std::move(opts)),
        data(options.data_dir),
        memory(options.session_memory_bytes),
        sessions(options.max_sessions, options.session_idle_timeout, options.session_eviction_grace),
        queue(options.render_workers, options.max_waiting_renders, options.max_waiting_renders_per_session) {}

  SessionContext session_context() {
    return SessionContext{&data, &cache, SceneLimits{options.max_builtin_size}, &memory};
  }

  ServerOptions options;
  DataDirectory data;
  VolumeCache cache;
  SessionMemory memory;  // before the sessions, which forget their records as they go
  SessionStore sessions;
  RenderQueue queue;
};

}  // namespace penumbra::server
