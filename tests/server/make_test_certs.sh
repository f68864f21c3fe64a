#!/bin/sh
# Makes throw-away TLS material for the service tests in OUTDIR:
#   ca.pem ca.key            the test CA
#   server.pem server.key    signed by the CA, for 127.0.0.1 and localhost (subjectAltName: gRPC
#                            checks the name it dialled against the SAN, not the CN)
#   client.pem client.key    a client certificate signed by the CA
#   rogue.pem rogue.key      a client certificate signed by another CA that the server never saw
# EC P-256 keys: quick to make, so each test process can make its own.
set -eu
[ $# -eq 1 ] || { echo "usage: $0 OUTDIR" >&2; exit 2; }
out=$1
mkdir -p "$out"
cd "$out"

key() { openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:P-256 -out "$1" 2>/dev/null; }

# ca NAME: a self-signed CA certificate NAME.pem with key NAME.key.
ca() {
  key "$1.key"
  openssl req -x509 -new -key "$1.key" -out "$1.pem" -days 2 -subj "/CN=meshd test $1" \
    -addext basicConstraints=critical,CA:TRUE -addext keyUsage=critical,keyCertSign,cRLSign
}

# leaf NAME CA USAGE [SAN]: NAME.pem with key NAME.key, signed by CA, for USAGE
# (serverAuth or clientAuth).
leaf() {
  key "$1.key"
  openssl req -new -key "$1.key" -out "$1.csr" -subj "/CN=meshd test $1"
  {
    echo "basicConstraints=CA:FALSE"
    echo "keyUsage=critical,digitalSignature"
    echo "extendedKeyUsage=$3"
    [ $# -lt 4 ] || echo "subjectAltName=$4"
  } >"$1.ext"
  openssl x509 -req -in "$1.csr" -CA "$2.pem" -CAkey "$2.key" -CAcreateserial -days 2 \
    -extfile "$1.ext" -out "$1.pem" 2>/dev/null
  rm -f "$1.csr" "$1.ext"
}

ca ca
ca rogue_ca
leaf server ca serverAuth "IP:127.0.0.1,DNS:localhost"
leaf client ca clientAuth
leaf rogue rogue_ca clientAuth
rm -f ./*.srl rogue_ca.key
