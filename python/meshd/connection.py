"""How a client reaches meshd: the channel's credentials and the metadata every call carries,
shared by the sync and the async client. It mirrors meshctl's --tls, --tls-ca, --tls-cert,
--tls-key, --tls-server-name and --token-file (or $MESHD_TOKEN).

    meshd.Client("mesh.example.org:443", tls=True, token="s3cret")
    meshd.Client(address, tls=meshd.tls_credentials(ca="ca.pem", cert="me.pem", key="me.key"))
"""

import os

import grpc

# meshd's results come in chunks of at most 1 MiB; 16 MiB leaves room for large snapshots.
MAX_MESSAGE_BYTES = 16 * 1024 * 1024


def _read(path):
    with open(path, "rb") as f:
        return f.read()


def tls_credentials(ca=None, cert=None, key=None):
    """grpc.ChannelCredentials for TLS: ca is a PEM file of the roots to trust (default the
    system's), cert and key a client certificate for servers started with --tls-client-ca."""
    if (cert is None) != (key is None):
        raise ValueError("tls_credentials: cert and key go together")
    return grpc.ssl_channel_credentials(
        root_certificates=_read(ca) if ca else None,
        private_key=_read(key) if key else None,
        certificate_chain=_read(cert) if cert else None)


class Connection:
    """Channel settings. tls: None or False for plain text, True for TLS with the system's roots,
    or grpc.ChannelCredentials. token: sent as "authorization: Bearer <token>" (the server's
    --token-file); None reads $MESHD_TOKEN like meshctl, "" sends none. tls_server_name: the
    name to check the server's certificate for, when it differs from the address."""

    def __init__(self, address, token=None, tls=None, tls_server_name=None, options=()):
        self.address = address
        if token is None:
            token = os.environ.get("MESHD_TOKEN", "")
        self.metadata = (("authorization", f"Bearer {token}"),) if token else ()
        if tls is True:
            tls = grpc.ssl_channel_credentials()
        self.credentials = tls or None
        self.options = [("grpc.max_receive_message_length", MAX_MESSAGE_BYTES), *options]
        if tls_server_name:
            self.options.append(("grpc.ssl_target_name_override", tls_server_name))

    def channel(self, grpc_module):
        """A channel of grpc (sync) or grpc.aio."""
        if self.credentials is not None:
            return grpc_module.secure_channel(self.address, self.credentials, self.options)
        return grpc_module.insecure_channel(self.address, self.options)
