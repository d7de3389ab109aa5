// Two hosts on one machine: two network namespaces joined by a veth pair, each with its own
// address, and Open MPI's TCP transport between them. mpirun runs in the first; its launcher
// agent enters the second with `ip netns exec` where it would ssh to another machine. Needs
// root and iproute2's `ip`; skipped, saying why, where the machine does not allow it.
#include <unistd.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/mpi_support.h"

namespace tessera {
namespace {

using test::quote;
using test::render_args;

class MpiTwoHosts : public test::MpiTest {
 protected:
  void SetUp() override {
    test::MpiTest::SetUp();
    if (IsSkipped()) return;
    if (geteuid() != 0) GTEST_SKIP() << "needs root to make network namespaces";
    if (std::system("command -v ip > /dev/null 2>&1") != 0) GTEST_SKIP() << "no `ip` (iproute2) to make network namespaces";
    const std::string id = std::to_string(getpid());
    a_ = "tessera-a-" + id, b_ = "tessera-b-" + id, veth_a_ = "tsa" + id, veth_b_ = "tsb" + id;
    const auto made = test::run_command(
        "set -e; ip netns add " + a_ + "; ip netns add " + b_ + "; ip link add " + veth_a_ + " type veth peer name " +
        veth_b_ + "; ip link set " + veth_a_ + " netns " + a_ + "; ip link set " + veth_b_ + " netns " + b_ +
        "; ip -n " + a_ + " addr add 10.77.0.1/24 dev " + veth_a_ + "; ip -n " + b_ + " addr add 10.77.0.2/24 dev " +
        veth_b_ + "; for n in " + a_ + " " + b_ + "; do ip -n $n link set lo up; done; ip -n " + a_ + " link set " +
        veth_a_ + " up; ip -n " + b_ + " link set " + veth_b_ + " up");
    if (made.exit_code != 0) GTEST_SKIP() << "network namespaces not permitted here: " << made.err;
  }
  void TearDown() override {
    if (!a_.empty()) test::run_command("ip netns del " + a_ + "; ip netns del " + b_);  // takes the veth pair along
  }
  // Bytes the first namespace's end of the veth pair sent and received.
  std::uint64_t veth_bytes() {
    const auto r = test::run_command("ip -n " + a_ + " -s -j link show " + veth_a_);
    const nlohmann::json link = nlohmann::json::parse(r.out, nullptr, false);
    if (link.is_discarded() || link.empty()) return 0;
    const nlohmann::json& stats = link[0]["stats64"];
    return stats["rx"]["bytes"].get<std::uint64_t>() + stats["tx"]["bytes"].get<std::uint64_t>();
  }
  std::string a_, b_, veth_a_, veth_b_;
};

TEST_F(MpiTwoHosts, OpenMpiOverTcpBetweenTwoNamespacesGivesTheSingleProcessBits) {
  const std::string dir = test::make_temp_dir("mpi-two-hosts");
  // Open MPI runs `AGENT HOST COMMAND...` where it would run `ssh HOST COMMAND...`.
  std::ofstream(dir + "/agent.sh") << "#!/bin/sh\nhost=$1; shift\ncase \"$host\" in 10.77.0.1) ns=" << a_
                                   << " ;; 10.77.0.2) ns=" << b_
                                   << " ;; *) echo \"agent: unknown host $host\" >&2; exit 1 ;; esac\n"
                                      "exec ip netns exec \"$ns\" /bin/sh -c \"$*\"\n";
  std::ofstream(dir + "/hosts") << "10.77.0.1 slots=1\n10.77.0.2 slots=1\n";
  ASSERT_EQ(test::run_command("chmod +x " + quote(dir + "/agent.sh")).exit_code, 0);
  const std::string opts = "-q --spp 16 --tile-size 8 --threads 1 --aov albedo";
  ASSERT_EQ(test::run_command(render_args(dir + "/one.exr", opts)).exit_code, 0);
  const std::uint64_t before = veth_bytes();
  // TCP only (no shared memory between the "hosts"), on the veth pair's subnet alone; Open MPI's
  // one-sided UCX component does not work over plain TCP. The ranks (whose environment the agent
  // does not carry) check no leaks: Open MPI keeps its allocations until exit.
  const auto r = test::run_command(
      "timeout 120 ip netns exec " + a_ + " mpirun --allow-run-as-root --hostfile " + quote(dir + "/hosts") +
      " -np 2 -x ASAN_OPTIONS=detect_leaks=0 --mca plm_rsh_agent " + quote(dir + "/agent.sh") +
      " --mca pml ob1 --mca btl tcp,self --mca osc ^ucx --mca btl_tcp_if_include 10.77.0.0/24"
      " --mca oob_tcp_if_include 10.77.0.0/24 " +
      render_args(dir + "/two.exr", opts));
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  test::expect_same_pixels(dir + "/one.exr", dir + "/two.exr");
  // The ranks talked over the veth pair: each wave (16 spp: 1, 2, 4, 8, 1) sends every pixel
  // from the rank that rendered it to the other, 40 bytes each (radiance sums 24, albedo sums
  // 12, sample count 4), plus headers and Open MPI's own messages.
  const std::uint64_t pixels = 5u * 40u * 36u * 40u, sent = veth_bytes() - before;
  EXPECT_GT(sent, pixels);
  EXPECT_LT(sent, 4 * pixels) << "more than the film exchange explains";
}

}  // namespace
}  // namespace tessera
