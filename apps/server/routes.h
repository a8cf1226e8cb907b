#pragma once
// The request handlers of HttpServer (the endpoint list is in http_server.h).
namespace httplib {
class Server;
}

namespace penumbra::server {

struct ServerContext;

void add_routes(httplib::Server& http, ServerContext& context);

}  // namespace penumbra::server
