#include "client/cli_options.h"

#include <cmath>
#include <cstdlib>
#include <set>

#include "core/common/error.h"
#include "core/common/text_file.h"

namespace meshd::cli {

namespace {

const std::set<std::string> kCommands = {"generate", "submit", "request", "watch", "cancel",
                                         "status",   "list",   "health",  "help"};

double number(const std::string& flag, const std::string& v) {
  char* end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0' || !std::isfinite(x))
    throw_invalid(flag, "expects a number (got '" + v + "')");
  return x;
}

int integer(const std::string& flag, const std::string& v) {
  const double x = number(flag, v);
  if (x != std::floor(x) || std::abs(x) > 1e9)
    throw_invalid(flag, "expects a whole number (got '" + v + "')");
  return static_cast<int>(x);
}

// N comma-separated numbers; `names` says which ("xmin,ymin,xmax,ymax") when they are not.
template <size_t N>
std::array<double, N> numbers(const std::string& flag, const std::string& v, const char* names) {
  std::array<double, N> x{};
  size_t start = 0;
  for (size_t k = 0; k < N; ++k) {
    const size_t comma = k + 1 < N ? v.find(',', start) : v.size();
    if (comma == std::string::npos || (k + 1 == N && v.find(',', start) != std::string::npos))
      throw_invalid(flag, std::string("expects ") + names + " (got " + quote_input(v) + ")");
    x[k] = number(flag, v.substr(start, comma - start));
    start = comma + 1;
  }
  return x;
}

// "xmin,ymin,xmax,ymax" with min < max.
std::array<double, 4> clip_box(const std::string& flag, const std::string& v) {
  const auto box = numbers<4>(flag, v, "xmin,ymin,xmax,ymax");
  if (!(box[0] < box[2] && box[1] < box[3]))
    throw_invalid(flag, "needs xmin < xmax and ymin < ymax (got " + quote_input(v) + ")");
  return box;
}

// "a,b" (`form` names them in the message, e.g. "x,y" or "W,H").
Vec2 pair(const std::string& flag, const std::string& v, const char* form = "x,y") {
  const auto xy = numbers<2>(flag, v, form);
  return {xy[0], xy[1]};
}

// "d" or "dx,dy", each > 0: the distance between a grid's samples.
Vec2 spacing(const std::string& flag, const std::string& v) {
  const Vec2 s = v.find(',') == std::string::npos ? Vec2{number(flag, v), number(flag, v)}
                                                  : pair(flag, v, "d or dx,dy");
  if (!(s.x > 0 && s.y > 0)) throw_invalid(flag, "must be > 0 (got " + quote_input(v) + ")");
  return s;
}

}  // namespace

CliOptions parse_cli(const std::vector<std::string>& args) {
  CliOptions o;
  if (const char* token = std::getenv("MESHD_TOKEN")) o.connection.token = token;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    std::string value;
    bool has_value = false;
    if (a.rfind("--", 0) == 0) {
      if (const auto eq = a.find('='); eq != std::string::npos) {
        value = a.substr(eq + 1);
        a = a.substr(0, eq);
        has_value = true;
      }
    }
    auto next = [&]() -> std::string {
      if (has_value) return value;
      if (i + 1 >= args.size()) throw_invalid(a, "needs a value");
      return args[++i];
    };
    if (a == "-h" || a == "--help")
      o.help = true;
    else if (a == "--json")
      o.json = true;
    else if (a == "--server")
      o.connection.server = next();
    else if (a == "--deadline") {
      o.connection.deadline_s = number(a, next());
      if (!(o.connection.deadline_s > 0)) throw_invalid(a, "must be > 0 seconds");
    } else if (a == "--tls")
      o.connection.tls = true;
    else if (a == "--tls-ca")
      o.connection.tls_ca = next();
    else if (a == "--tls-cert")
      o.connection.tls_cert = next();
    else if (a == "--tls-key")
      o.connection.tls_key = next();
    else if (a == "--tls-server-name")
      o.connection.tls_server_name = next();
    else if (a == "--token-file")
      o.connection.token = read_first_line(next(), a);
    else if (a == "-o" || a == "--output")
      o.outputs.push_back(next());
    else if (a == "--format")
      o.format = next();
    else if (a == "--frames")
      o.frames_dir = next();
    else if (a == "--backend") {
      o.backend = next();
      if (*o.backend != "auto" && *o.backend != "gpu" && *o.backend != "cpu")
        throw_invalid(a, "must be auto, gpu or cpu (got '" + *o.backend + "')");
    } else if (a == "--priority")
      o.priority = integer(a, next());
    else if (a == "--snapshot-every")
      o.snapshot_every = integer(a, next());
    else if (a == "--timeout")
      o.timeout_s = number(a, next());
    else if (a == "--label")
      o.label = next();
    else if (a == "--circle")
      o.circle = number(a, next());
    else if (a == "--sphere")
      o.sphere = number(a, next());
    else if (a == "--hole")
      o.hole = number(a, next());
    else if (a == "--h0")
      o.h0 = number(a, next());
    else if (a == "--seed")
      o.seed = static_cast<uint64_t>(integer(a, next()));
    else if (a == "--rectangle") {
      const Vec2 wh = pair(a, next(), "W,H");
      o.rectangle = {wh.x, wh.y};
    } else if (a == "--sdf-grid")
      o.sdf_grid = next();
    else if (a == "--sdf-grid-origin")
      o.sdf_grid_origin = pair(a, next());
    else if (a == "--sdf-grid-spacing")
      o.sdf_grid_spacing = spacing(a, next());
    else if (a == "--import")
      o.gis.path = next();
    else if (a == "--layer")
      o.gis.layer = next();
    else if (a == "--where")
      o.gis.where = next();
    else if (a == "--clip")
      o.gis.clip = clip_box(a, next());
    else if (a == "--simplify") {
      o.simplify = number(a, next());
      if (!(*o.simplify > 0)) throw_invalid(a, "must be > 0 (a tolerance of F times h0)");
    } else if (a == "--from-crs")
      o.gis.from_crs = next();
    else if (a == "--to-crs")
      o.gis.to_crs = next();
    else if (a == "--import-name")
      o.import_name = next();
    else if (a == "--subtract-from-clip")
      o.subtract_from_clip = true;
    else if (a == "--size-grid")
      o.size_grid.path = next();
    else if (a == "--size-grid-origin")
      o.size_grid.origin = pair(a, next());
    else if (a == "--size-grid-spacing")
      o.size_grid.spacing = spacing(a, next());
    else if (a == "--gradation")
      o.gradation = number(a, next());
    else if (a == "--feature")
      o.feature = numbers<3>(a, next(), "elements,h_min,h_max");
    else if (a == "--grade") {
      o.grade = numbers<3>(a, next(), "h_min,slope,h_max");
      const auto [h_min, slope, h_max] = *o.grade;
      if (!(h_min > 0 && slope >= 0 && h_max >= h_min))
        throw_invalid(a, "needs h_min > 0, slope >= 0 and h_max >= h_min");
    } else if (a == "--state")
      o.state = next();
    else if (!a.empty() && a[0] == '-')
      throw_invalid(a, "unknown flag; see meshctl --help");
    else if (o.command.empty()) {
      if (!kCommands.count(a)) throw_invalid(a, "unknown command; see meshctl --help");
      o.command = a;
    } else
      o.args.push_back(a);
  }
  if (o.command == "help") {
    o.help = true;
    o.command = o.args.empty() ? "" : o.args[0];
  }
  if (o.command.empty()) o.help = true;
  return o;
}

std::string help_text(const std::string& command) {
  const std::string connection = R"(
Connection flags (every command):
  --server HOST:PORT      meshd's address (default 127.0.0.1:50051)
  --deadline SECONDS      deadline of each call (default 600)
  --tls                   use TLS with the system's roots; --tls-ca FILE trusts FILE instead
  --tls-cert FILE --tls-key FILE   present a client certificate
  --tls-server-name NAME  check the server's certificate for NAME
  --token-file FILE       send "authorization: Bearer <first line of FILE>" (or $MESHD_TOKEN)
  --json                  print machine-readable JSON (one object per line) instead of text
)";
  const std::string request_flags = R"(
Request (a text-format meshd.v1.MeshRequest file, or flags for simple shapes):
  --circle R | --rectangle W,H   a disk of radius R, or a W x H rectangle, centred at 0
  --sphere R                     a ball of radius R, centred at 0: tetrahedra (3D)
  --hole R                       minus a disk (a ball, with --sphere) of radius R at the centre
  --h0 H                         edge length (required with the shape flags)
  --seed N
Signed-distance grid (DistMesh's dmatrix: a segmented image's distance transform):
  --sdf-grid FILE.npy      a 2-D NumPy array (float32 or float64) of signed distances,
                           negative inside, [row j, column i] at (x0 + i dx, y0 + j dy), rows
                           counted upwards; the domain is where its bilinear interpolant is < 0.
                           Alone with --h0; its boundary group is named after the file
  --sdf-grid-origin X0,Y0  where sample [0, 0] lies (default 0,0)
  --sdf-grid-spacing D|DX,DY   the distance between samples (default 1: pixels)
Import (a polygon layer of a GeoJSON, Shapefile, GeoPackage, KML, DXF, ... file, via GDAL):
  --import FILE            the layer as a shape: the union of its polygons, holes subtracted.
                           Alone (with --h0) it is the geometry; with a request file it fills
                           each placeholder there: a shape with only a name (the group name)
  --layer NAME             the layer (default the first)
  --where EXPR             OGR SQL attribute filter, e.g. "name = 'Isla Grande'"
  --clip XMIN,YMIN,XMAX,YMAX   clip to this box, in the output CRS
  --subtract-from-clip     the geometry is the clip box minus the import (the sea round land)
  --simplify F             simplify, keeping topology, to a tolerance of F * h0; rings of
                           less area than the tolerance squared are dropped and counted
  --grade H_MIN,SLOPE,H_MAX    add a size term graded with the distance d to the import's
                           outline: h0 * min(H_MAX, H_MIN + SLOPE * d), SLOPE per output-CRS
                           unit (a coast at H_MIN that grows offshore)
  --to-crs CRS             output CRS (EPSG:NNNN, WKT, PROJ); default: the UTM zone of the
                           data's centre for data in degrees, else the file's CRS; 'none' keeps
                           the coordinates as they are
  --from-crs CRS           the data's CRS where the file has none (or a wrong one)
  --import-name NAME       boundary-group name of the import (default the layer's name)
Size field (added to the request file's terms: h is the minimum of them all):
  --size-grid FILE         relative sizes on a regular grid, read bilinearly: a NumPy .npy
                           array indexed [row j, column i], row j at y = y0 + j * dy (upwards),
                           or a GeoTIFF / GDAL raster, north-up, pixel centres as samples
  --size-grid-origin X,Y   where sample [0, 0] lies (required for .npy; overrides a raster's)
  --size-grid-spacing D | DX,DY   the samples' spacing (required for .npy; overrides a raster's)
  --feature K,H_MIN,H_MAX  a feature-size term: about K edges across the domain's narrow
                           parts (channels), h clamped to [H_MIN, H_MAX]
  --gradation G            the edge length may grow by at most G per length unit, (0, 10]
Job options (override the file's):
  --backend auto|gpu|cpu  --priority P (-10..10)  --label TEXT
)";
  if (command == "generate") {
    return "usage: meshctl generate [REQUEST.textproto] [flags]\n\n"
           "Meshes a request on meshd and streams its progress; writes the mesh.\n\n"
           "  -o FILE                write the mesh; the format follows the extension: .msh\n"
           "                         (MSH 4.1), .msh22, .vtu, .svg; may be given several times\n"
           "  --format NAME          msh41, msh41-binary, msh22, vtu or svg for every -o\n"
           "  --frames DIR           write an SVG of each snapshot to DIR (of a volume, its\n"
           "                         surface; snapshots every 10 iterations unless\n"
           "                         --snapshot-every K says otherwise)\n"
           "  --snapshot-every K     ask for a snapshot every K iterations\n" +
           request_flags + connection +
           "\nExamples:\n"
           "  meshctl generate examples/g2_square_hole.textproto -o g2.msh -o g2.svg\n"
           "  meshctl generate --circle 1 --h0 0.05 -o disk.vtu --backend cpu\n"
           "  meshctl generate examples/g1_disk.textproto --frames frames/ --json\n"
           "  meshctl generate --sdf-grid blob.npy --sdf-grid-spacing 0.01 --h0 0.02 -o b.svg\n"
           "  meshctl generate --import examples/gis/island.geojson --h0 500 -o island.msh\n"
           "  meshctl generate --import coast.gpkg --layer land --subtract-from-clip \\\n"
           "      --clip 290000,4385000,390000,4460000 --simplify 0.5 --h0 500 -o sea.msh\n"
           "  meshctl generate --import coast.gpkg --clip 290000,4385000,390000,4460000 \\\n"
           "      --subtract-from-clip --h0 250 --grade 1,0.0005,8 -o graded_sea.msh\n"
           "  meshctl generate examples/gis/island_ocean.textproto \\\n"
           "      --import examples/gis/island.geojson -o ocean.msh\n"
           "  meshctl generate --rectangle 4,2 --h0 0.02 --size-grid sizes.npy \\\n"
           "      --size-grid-origin -2,-1 --size-grid-spacing 0.1 --gradation 0.2 -o graded.msh\n";
  }
  if (command == "submit") {
    return "usage: meshctl submit [REQUEST.textproto] [flags]\n\n"
           "Queues a request and prints its job id at once; the job runs on without the client.\n"
           "  --timeout SECONDS      the job's time limit from now, queue included\n" +
           request_flags + connection +
           "\nExample:\n  id=$(meshctl submit examples/g1_disk.textproto) && meshctl watch $id -o "
           "g1.msh\n";
  }
  if (command == "request") {
    return "usage: meshctl request [REQUEST.textproto] [flags] [-o FILE]\n\n"
           "Writes the request that generate would send, in text format, to FILE or stdout,\n"
           "without a server: an import or the shape flags kept as a request file to edit,\n"
           "rerun or benchmark (meshbench reads it).\n" +
           request_flags +
           "\nExample:\n  meshctl request --import coast.gpkg --subtract-from-clip \\\n"
           "      --clip 290000,4385000,390000,4460000 --h0 500 -o sea.textproto\n";
  }
  if (command == "watch") {
    return "usage: meshctl watch JOB_ID [-o FILE]... [--frames DIR]\n\n"
           "Streams a job's events from the start (a finished job: its result at once) and\n"
           "writes its mesh like generate.\n" +
           connection + "\nExample:\n  meshctl watch j0000000001-2f3a1c -o mesh.msh\n";
  }
  if (command == "cancel") {
    return "usage: meshctl cancel JOB_ID\n\nCancels a queued or running job and prints its "
           "state.\n" +
           connection;
  }
  if (command == "status") {
    return "usage: meshctl status JOB_ID\n\nPrints a job's state, progress and, when done, its "
           "statistics.\n" +
           connection;
  }
  if (command == "list") {
    return "usage: meshctl list [--state queued|running|succeeded|failed|cancelled]\n\n"
           "Lists the jobs the server holds, in submission order.\n" +
           connection;
  }
  if (command == "health") {
    return "usage: meshctl health\n\nAsks grpc.health.v1: exit 0 when SERVING, 10 when not "
           "serving, 3 when unreachable.\n" +
           connection;
  }
  return R"(usage: meshctl COMMAND [args] [flags]

The command-line client of meshd, the DistMesh mesh service.

Commands:
  generate [REQUEST]   mesh a request, show progress, write the mesh (-o FILE)
  submit [REQUEST]     queue a request, print its job id
  request [REQUEST]    write the request generate would send (no server needed)
  watch JOB_ID         stream a job's events and write its mesh
  cancel JOB_ID        cancel a job
  status JOB_ID        show a job
  list                 list the server's jobs
  health               ask whether the server is serving

'meshctl help COMMAND' or 'meshctl COMMAND --help' shows a command's flags and examples.

Exit codes: 0 ok, 1 failed, 2 bad request or command line, 3 server unavailable,
4 deadline exceeded, 5 cancelled, 6 request too large, 7 no such job, 8 unauthenticated,
9 failed precondition (e.g. no GPU), 10 not serving, 11 bad result or output file.
)";
}

}  // namespace meshd::cli
